// A scene made runnable: its bodies, built from a SceneSpec and one mesh per body, stepped
// together.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "deformable_sim/core/base/spec_error.h"
#include "deformable_sim/core/bodies/body_list.h"
#include "deformable_sim/core/contact/body_contact.h"
#include "deformable_sim/core/contact/contact_step.h"
#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/core/session/energy_watch.h"
#include "deformable_sim/core/session/scene.h"
#include "deformable_sim/core/surface_bodies/embedded_surface.h"

namespace deformable_sim::core {

class Simulation {
 public:
  /// meshes[i] is the mesh of spec.bodies[i]. Throws SpecError (a std::invalid_argument) naming
  /// the key of the offending entry ("bodies[0].fixed[1]: selects no node") for bad selections,
  /// loads and materials.
  Simulation(const SceneSpec& spec, std::vector<Mesh> meshes);

  double dt() const { return dt_; }
  /// Changes the step between steps. Throws std::invalid_argument unless finite and > 0.
  void setDt(double dt);
  long stepCount() const { return step_count_; }
  double time() const { return time_; }  ///< s, simulated since the start

  BodyList& bodies() { return bodies_; }
  const BodyList& bodies() const { return bodies_; }
  /// Throws std::out_of_range naming the body if there is none of that name.
  Body& body(const std::string& name);
  /// Index of the body of that name in bodies(), or -1.
  int bodyIndex(const std::string& name) const;
  /// The scene's wrench_radius of bodies()[index], m.
  double wrenchRadius(int index) const { return wrench_radii_[index]; }

  /// One step of every body; reports[i] belongs to bodies()[i]. `reports` is resized once.
  /// The watchdog: a body whose step leaves a non-finite position, velocity or constraint force
  /// or whose solve saw a non-finite residual (absurd input that got past validation, an
  /// overflow), or whose energy leaps past what the step could have given it
  /// (EnergyWatch: a blow-up that is still finite), gets its positions from before the step back
  /// and stops (velocities zero: infinite damping for that step; constraint forces zero), and its
  /// report says `recovered` (and `energy_leapt` for a leap).
  void step(std::vector<StepReport>& reports);
  /// Steps of bodies()[index] that the watchdog undid, since construction.
  long recoveries(int index) const { return recoveries_[index]; }

  /// Obstacles of the contact effect; their poses may be changed between steps (a pose changed
  /// before a step is reached within it: the obstacle moves, and carries what sticks to it).
  std::vector<PlacedShape>& obstacles() { return obstacles_; }
  const std::vector<PlacedShape>& obstacles() const { return obstacles_; }
  const std::optional<ContactSettings>& contact() const { return contact_; }
  /// What bodies()[b] felt from each obstacle in the last step (empty without contact, or for a
  /// body contact does not act on).
  const std::vector<ContactLoad>& obstacleContacts(int b) const;
  /// Body steps that ran the contact effect (zero without it): its counter, as Body's.
  long contactSteps() const { return contact_step_ ? contact_step_->obstacleSteps() : 0; }
  /// Steps that ran contact between bodies or of a body with itself (zero unless the scene turns
  /// it on for some body), and that contact, or null.
  long bodyContactSteps() const { return contact_step_ ? contact_step_->bodySteps() : 0; }
  const BodyContact* bodyContact() const {
    return contact_step_ ? contact_step_->bodyContact() : nullptr;
  }
  /// Obstacle contact's last problem, when it is solved as one (ContactSettings::one_problem).
  const ContactImpulses* obstacleImpulses() const {
    return contact_step_ ? contact_step_->obstacleImpulses() : nullptr;
  }

  /// Throws SpecError (key "bodies[i]" of the body inside) naming both bodies and the
  /// depth when two bodies that touch each other start deeper inside each other than the pair's
  /// contact tolerance (BodyContact::kStartingOverlap). Call once the bodies have the surfaces
  /// they were made from.
  void refuseBodiesInsideEachOther() const;

  /// Quasi-static equilibrium of every body.
  std::vector<StaticReport> solveStatic();

  /// The surface that bodies()[b] was made from (a body from `mesh: {surface: ..}`), carried by
  /// its grid, or null. Its positions are those of its last update(bodies()[b].positions()):
  /// whoever draws it updates it, the step does not.
  const EmbeddedSurface* embeddedSurface(int b) const;
  EmbeddedSurface* embeddedSurface(int b);
  /// Gives bodies()[b] the surface it was made from. Throws std::invalid_argument when the
  /// surface refers to nodes that the body's mesh does not have.
  void setEmbeddedSurface(int b, EmbeddedSurface surface);

 private:
  /// Builds bodies()[b] from spec.bodies[b] and its mesh: groups, fixed nodes and loads.
  void addBody(const SceneSpec& spec, size_t b, Mesh mesh);
  /// Body b's own step, undone by the watchdog when it leaves a non-finite value.
  void stepBody(int b, StepReport& report);
  /// The watchdog: body b back where it started the step, at rest.
  void undoStep(int b, StepReport& report);

  double dt_;
  int threads_ = 1;  ///< the scene's solver threads: bodies step side by side on them
  StaticSettings statics_;
  long step_count_ = 0;
  double time_ = 0.0;
  BodyList bodies_;
  std::vector<double> wrench_radii_;
  std::optional<ContactSettings> contact_;
  std::optional<ContactStep> contact_step_;  ///< with the contact effect
  std::vector<PlacedShape> obstacles_;
  std::vector<long> recoveries_;             ///< per body: steps the watchdog undid
  std::optional<EnergyWatch> energy_watch_;  ///< built with the bodies
  /// Per body (sized by setEmbeddedSurface only), its embedded surface if it has one.
  std::vector<std::optional<EmbeddedSurface>> embedded_surfaces_;
};

}  // namespace deformable_sim::core
