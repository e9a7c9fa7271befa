// Contact with rigid obstacles (the `contact` effect). After each step, nodes that ended up inside
// an obstacle are put back on its surface and their velocity into it, relative to the obstacle's,
// removed. A node that touches an obstacle without sliding on it is then held in the next step's
// implicit solve, at its point of the obstacle (which may move: a robot's finger), so the
// obstacle supports and carries the body through the solve (a resting body is not
// over-compressed, a squeezed one is lifted by friction). It is let go when the constraint would
// pull it into the obstacle or, by Coulomb's law applied to the body's held nodes on that
// obstacle together, when their tangential force exceeds μ times their normal force (they
// slide). Stable at any stiffness and step; costs nothing when the scene does not enable it.
#pragma once

#include <Eigen/Geometry>
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

/// What a body felt from one obstacle in the last step.
struct ContactLoad {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   ///< on the body, world frame, N
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  ///< on the body about the world origin, N m
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< mean of the touching nodes, m
  int points = 0;                                    ///< nodes touching it after the step
  double penetration = 0.0;  ///< deepest a node was found inside it before being put back, m
};

/// Which nodes touch which obstacle, from step to step. Sized once per body and per number of
/// obstacles; allocates nothing while that number stays the same.
class ContactState {
 public:
  explicit ContactState(int num_nodes);

  /// Before a step, with the obstacles where they will be at its end: holds the free nodes that
  /// stick to an obstacle at their point of it.
  void hold(Body& body, const std::vector<PlacedShape>& obstacles);
  /// After the step of `dt` s: lets the held nodes go. While the constraint forces of a body's
  /// nodes held on one obstacle together push out of it within the friction cone, those that
  /// push stay touching (held in the next step); else they all start to slide.
  void release(Body& body, const std::vector<PlacedShape>& obstacles,
               const ContactSettings& settings, double dt);
  /// Projects the free nodes out of every obstacle and records them as touching; an obstacle's
  /// velocity is that of its rigid motion from `start_poses[k]` to its pose within the step.
  /// Returns the number of nodes touching an obstacle.
  int project(Body& body, const std::vector<PlacedShape>& obstacles,
              const std::vector<Eigen::Isometry3d>& start_poses, const ContactSettings& settings,
              double dt);
  /// Per obstacle (as given to project()), what the body felt from it in the last step.
  const std::vector<ContactLoad>& obstacleContacts() const { return contacts_; }
  /// The obstacles were replaced by others: no node touches any.
  void forget();

 private:
  /// A body's held nodes on one obstacle, judged together by Coulomb's law.
  struct Patch {
    double pushing = 0.0, mass = 0.0;
    Eigen::Vector3d sliding = Eigen::Vector3d::Zero();
    bool sticks = true;
    Eigen::Vector3d slip = Eigen::Vector3d::Zero();  ///< velocity the sliding nodes gain
    double transmitted = 1.0;  ///< fraction of the tangential force the obstacle exerts
  };

  /// Sums the held nodes' constraint forces per obstacle and judges each patch.
  void judgePatches(const Body& body, const std::vector<PlacedShape>& obstacles,
                    const ContactSettings& settings, double dt);
  /// The force of the obstacle on node i, its contact from here on, and the node's velocity.
  void applyFriction(Body& body, int i, const Eigen::Vector3d& obstacle_velocity,
                     const Eigen::Vector3d& normal, const ContactSettings& settings, double dt);
  void resizeForObstacles(size_t count);
  void addForce(int k, const Eigen::Vector3d& at, const Eigen::Vector3d& force);
  Eigen::Vector3d worldNormal(const std::vector<PlacedShape>& obstacles, int i) const;

  std::vector<int> obstacle_;            ///< the obstacle node i touches, -1: none
  std::vector<Eigen::Vector3d> point_;   ///< node i's point of it, in the obstacle's frame
  std::vector<Eigen::Vector3d> normal_;  ///< outward normal there, in the obstacle's frame
  std::vector<std::uint8_t> sticking_;   ///< touching without sliding: held in the next step
  std::vector<int> held_;                ///< nodes held in the present step
  std::vector<std::uint8_t> held_flag_;  ///< the same, per node
  std::vector<ContactLoad> contacts_;
  std::vector<Patch> patches_;
};

}  // namespace deformable_sim::core
