// Contact with rigid obstacles (the `contact` effect). After each step, nodes that ended up inside
// an obstacle are put back on its surface and their velocity into it removed. A node that touches
// an obstacle without sliding is then held in the next step's implicit solve, so the obstacle
// supports the body through the solve (a resting body is not over-compressed), and let go when
// the constraint would pull it into the obstacle or, by Coulomb's law applied to the body's held
// nodes together, when their tangential force exceeds μ times their normal force (it slides).
// Stable at any stiffness and step; costs nothing when the scene does not enable it.
#pragma once

#include <cstdint>
#include <vector>

#include "deformable_sim/core/body.h"
#include "deformable_sim/core/shape.h"

namespace deformable_sim::core {

struct ContactSettings {
  double friction = 0.5;  ///< Coulomb coefficient μ >= 0; with 0 a node never sticks
  bool bodies = false;    ///< bodies touch one another (core/body_contact.h)
  bool self = false;      ///< a body touches itself
};

/// Which nodes touch an obstacle, from step to step. Sized once per body; allocates nothing after.
class ContactState {
 public:
  explicit ContactState(int num_nodes)
      : normal_(num_nodes, Eigen::Vector3d::Zero()), held_(num_nodes, 0) {}

  /// Before a step: holds the free nodes that touch an obstacle.
  void hold(Body& body);
  /// After the step of `dt` s: lets the held nodes go. While their constraint forces together
  /// push out of the obstacles within the friction cone, those that push stay touching (held
  /// in the next step); else they all start to slide.
  void release(Body& body, const ContactSettings& settings, double dt);
  /// Projects the free nodes out of every obstacle and records them as touching. Returns the
  /// number of nodes touching an obstacle.
  int project(Body& body, const std::vector<PlacedShape>& obstacles,
              const ContactSettings& settings);

 private:
  std::vector<Eigen::Vector3d> normal_;  ///< outward normal of the obstacle touched, zero: none
  std::vector<std::uint8_t> held_;
};

}  // namespace deformable_sim::core
