// A body as contact between bodies sees it: where a point of its surface is, how fast it moves,
// and how it answers an impulse there. A finite-element body answers as its implicit step would
// have (core/bodies/implicit_response.h; constrained nodes not at all), a rigid or pseudo-rigid
// body with its whole motion (its mass and inertia, or its mass and Euler tensor), gathered in
// increments of its coordinates and handed to it once the contact is resolved.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>

#include "deformable_sim/core/bodies/body.h"
#include "deformable_sim/core/bodies/implicit_response.h"
#include "deformable_sim/core/geometry/surface_point.h"

namespace deformable_sim::core {

class ContactParticipant {
 public:
  /// Sizes the scratch for `body`; allocates only here.
  explicit ContactParticipant(const Body& body);

  /// Takes the body's state after its step of `dt`; a rigid or pseudo-rigid body starts with no
  /// change. `new_step`: false for a later round of the same step, whose answers are still good.
  void begin(Body& body, double dt, bool new_step = true);
  /// Gives the body the change of its coordinates (a finite-element body's whole-body answers
  /// are kept apart until here), and the constraint forces its impulses asked of its held nodes.
  void end(Body& body);

  Eigen::Vector3d position(const SurfacePoint& point) const;
  Eigen::Vector3d velocity(const SurfacePoint& point) const;
  /// n^T W n: how fast the point moves along the unit normal n per unit impulse along it (a
  /// quadratic form in n, whatever its length).
  double inverseMass(const SurfacePoint& point, const Eigen::Vector3d& normal) const;
  /// W itself: the point's velocity change per unit impulse there; `local`: a finite-element
  /// body's nodes answering alone, by their lumped masses.
  Eigen::Matrix3d compliance(const SurfacePoint& point, bool local = false) const;
  /// Linear solves a finite-element body took in this step to answer impulses.
  int solves() const { return response_ ? response_->solves() : 0; }
  /// The point's body takes `impulse` (N s) there within the step: its velocities change by
  /// W impulse and, the step being x = x0 + dt v, its positions by dt W impulse (`local`: see
  /// compliance()).
  void push(const SurfacePoint& point, const Eigen::Vector3d& impulse, bool local = false);
  /// A small correction of positions only (what is left inside after the impulses), momentum
  /// untouched: a finite-element body's nodes move by their lumped inverse masses alone, so that
  /// the correction stays where it is needed; other bodies with their whole motion.
  void nudge(const SurfacePoint& point, const Eigen::Vector3d& shift);
  double nudgeCompliance(const SurfacePoint& point, const Eigen::Vector3d& normal) const;
  /// The part of the point's weight on nodes free to move: 1 for a rigid or pseudo-rigid body,
  /// 0 where a finite-element body is held all over.
  double movable(const SurfacePoint& point) const;

 private:
  /// The rest arm X - Xc of the point (rigid and pseudo-rigid bodies).
  Eigen::Vector3d arm(const SurfacePoint& point) const;
  /// How the body's coordinates change when the point takes `amount`: the centre by amount / M,
  /// the gradient (or its rate) by the returned matrix.
  Eigen::Matrix3d gradientChange(const Eigen::Vector3d& arm, const Eigen::Vector3d& amount) const;

  /// A finite-element body: `amount` at the point, answered by its nodes alone (lumped masses;
  /// a point that shifts its cells, by them as one mass), added to `state`.
  void addLumped(const SurfacePoint& point, const Eigen::Vector3d& amount,
                 Eigen::VectorXd& state) const;
  /// The mass of the point's free nodes (a point that shifts its cells moves them as one).
  double clusterMass(const SurfacePoint& point) const;
  /// A finite-element body: `amount` at the point, answered by the whole body, added to `state`.
  void addAnswer(const SurfacePoint& point, const Eigen::Vector3d& amount,
                 Eigen::VectorXd& state) const;

  const Body* body_ = nullptr;
  Eigen::VectorXd* x_ = nullptr;  ///< a finite-element body's own state, changed in place
  Eigen::VectorXd* v_ = nullptr;
  double dt_ = 0.0;  ///< of the step
  /// Finite elements: columns solved lazily, so `mutable`; and the velocity change the
  /// whole-body answers made so far (not yet in the state).
  mutable std::optional<ImplicitResponse> response_;
  Eigen::VectorXd velocity_change_of_nodes_;
  Eigen::Vector3d rest_centre_ = Eigen::Vector3d::Zero();
  double inverse_mass_ = 0.0;  ///< of the whole body
  Eigen::Matrix3d gradient_ = Eigen::Matrix3d::Identity();
  /// Rigid: the inverse inertia in the world frame; pseudo-rigid: the inverse Euler tensor.
  Eigen::Matrix3d inverse_moment_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d centre_change_ = Eigen::Vector3d::Zero(),
                  velocity_change_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d gradient_change_ = Eigen::Matrix3d::Zero(),
                  rate_change_ = Eigen::Matrix3d::Zero();
  Eigen::VectorXd base_x_, base_v_;  ///< rigid and pseudo-rigid: the nodes after the step
};

}  // namespace deformable_sim::core
