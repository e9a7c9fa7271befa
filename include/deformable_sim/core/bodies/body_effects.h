// What a body simulates: the effects a scene enables for it (what is absent is not computed),
// and how often each one's code ran, so that a test can see that an effect off costs nothing.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "deformable_sim/core/bodies/body_model.h"
#include "deformable_sim/core/elements/plasticity.h"

namespace deformable_sim::core {

/// Rayleigh damping C = mass M + stiffness K'.
struct RayleighDamping {
  double mass = 0.0;       ///< alpha, 1/s
  double stiffness = 0.0;  ///< beta, s
};

/// The effects a body simulates. What is absent is not computed.
struct BodyEffects {
  bool warping = false;                    ///< corotation; false = plain linear FEM (R = I)
  std::optional<Eigen::Vector3d> gravity;  ///< m/s^2
  std::optional<RayleighDamping> damping;
  std::optional<PlasticitySettings> plasticity;  ///< dynamic steps only (not the static solve)
  bool stress_colouring = false;  ///< the surface marker is coloured by strain (ROS layer)
  /// The force each constraint exerts (reactionForces()); grasps and contact friction read it.
  bool reactions = true;
  /// The body's own say on the contact effect's `bodies` and `self` (its `effects: {contact:
  /// ...}`); unset: the scene's. Both need the scene's contact effect.
  std::optional<bool> contact_bodies, contact_self;
};

/// How often each effect's code ran: a step counts once per effect it computed. An effect that is
/// off keeps its count at zero.
struct EffectCounters {
  long warping = 0;     ///< element (or body) rotations updated
  long gravity = 0;     ///< gravity added to the loads
  long damping = 0;     ///< Rayleigh damping in the step's matrix
  long plasticity = 0;  ///< plastic flow and its forces
  long reactions = 0;   ///< constraint forces computed
};

/// The effects of a body of `model`: its own, or the scene's. Plasticity inherited from the
/// scene is for its finite-element bodies only; with contact, those compute their reactions
/// (contact decides stick or slip from them).
BodyEffects effectsOf(BodyModel model, const BodyEffects& scene,
                      const std::optional<BodyEffects>& own, bool contact);

/// Names of the effects a body of `model` simulates with `effects`, in the scene file's words
/// (warping, gravity, damping, plasticity, stress_colouring, reactions); contact is the scene's.
std::vector<std::string> effectNames(const BodyEffects& effects, BodyModel model);

}  // namespace deformable_sim::core
