// A body as contact between bodies sees it: where a point of its surface is, how fast it moves,
// and how it answers an impulse there. A finite-element body's nodes move alone (their lumped
// masses; constrained nodes not at all); a rigid or pseudo-rigid body answers with its whole
// motion (its mass and inertia, or its mass and Euler tensor), gathered in increments of its
// coordinates and handed to it once the contact is resolved.
#pragma once

#include <Eigen/Core>
#include <array>

#include "deformable_sim/core/body.h"

namespace deformable_sim::core {

/// A point of a body's surface: a node (count 1) or a point of a triangle (count 3, barycentric).
struct SurfacePoint {
  std::array<int, 3> nodes{};
  std::array<double, 3> weights{};
  int count = 1;
};

class ContactParticipant {
 public:
  /// Sizes the scratch for `body`; allocates only here.
  explicit ContactParticipant(const Body& body);

  /// Takes the body's state after its step; a rigid or pseudo-rigid body starts with no change.
  void begin(Body& body);
  /// Gives a rigid or pseudo-rigid body the change of its coordinates (a finite-element body was
  /// changed in place).
  void end(Body& body) const;

  Eigen::Vector3d position(const SurfacePoint& point) const;
  Eigen::Vector3d velocity(const SurfacePoint& point) const;
  /// n^T W n: how far the point moves along the unit normal n per unit impulse along it.
  double inverseMass(const SurfacePoint& point, const Eigen::Vector3d& normal) const;
  /// The point's body takes `impulse` (N s) there: its velocities change by W impulse.
  void push(const SurfacePoint& point, const Eigen::Vector3d& impulse);
  /// The same for the positions: they change by W `shift` (kg m), momentum untouched.
  void displace(const SurfacePoint& point, const Eigen::Vector3d& shift);

 private:
  /// The rest arm X - Xc of the point (rigid and pseudo-rigid bodies).
  Eigen::Vector3d arm(const SurfacePoint& point) const;
  /// How the body's coordinates change when the point takes `amount`: the centre by amount / M,
  /// the gradient (or its rate) by the returned matrix.
  Eigen::Matrix3d gradientChange(const Eigen::Vector3d& arm, const Eigen::Vector3d& amount) const;

  const Body* body_ = nullptr;
  Eigen::VectorXd* x_ = nullptr;  ///< a finite-element body's own state, changed in place
  Eigen::VectorXd* v_ = nullptr;
  std::vector<double> inverse_masses_;  ///< per node; zero where constrained
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
