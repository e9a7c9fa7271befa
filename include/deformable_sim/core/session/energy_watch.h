// The watchdog's second check (Simulation::step): a step after which a body has far more energy
// (kinetic and elastic) than its energy before the step and what the step could have given it
// account for. It catches blow-ups that stay finite (contact feeding on itself: two bodies at 1e150
// J after a hundred steps) on their first steps, long before anything overflows.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <vector>

#include "deformable_sim/core/bodies/body_list.h"
#include "deformable_sim/core/contact/contact.h"
#include "deformable_sim/core/geometry/shape.h"

namespace deformable_sim::core {

class EnergyWatch {
 public:
  /// A step leaps when a body's energy after it exceeds this many times the bound below.
  /// Blow-ups grow by factors of ten to a million a step, so a wide margin costs them a step or
  /// two, while legitimate steps stay far below it.
  static constexpr double kLeap = 100.0;
  /// Kinetic energy any body may have regardless: that of moving as a whole at this speed, m/s
  /// (a body at rest with nothing on it ends a step with round-off).
  static constexpr double kFloorSpeed = 1e-3;

  /// Sized for `bodies` as built; allocates nothing in the steps after.
  explicit EnergyWatch(const BodyList& bodies);

  /// Before a step of dt s, with the obstacles where it takes them: each body's velocities and
  /// energy (kinetic and elastic), and how fast the obstacles move.
  void before(const BodyList& bodies, const std::vector<PlacedShape>& obstacles, double dt);
  /// After every body's step of dt s: adds what held nodes were driven at to driveSpeed(), and
  /// how fast obstacles put back what was inside them: `obstacle_loads(b)` is what body b felt
  /// from each obstacle (ContactLoad::penetration, the deepest a point was before being put
  /// back, moved within the step).
  template <typename ObstacleLoads>
  void after(const BodyList& bodies, double dt, const ObstacleLoads& obstacle_loads) {
    heldNodes(bodies);
    for (int b = 0; b < static_cast<int>(bodies.size()); ++b) {
      for (const ContactLoad& load : obstacle_loads(b)) {
        drive_speed_ = std::max(drive_speed_, load.penetration / dt);
      }
    }
  }

  /// The fastest of: any node at the step's start, a held node in the step (a moving grasp or
  /// fixed node), a point of an obstacle near the bodies, a point an obstacle put back out of
  /// itself, and contact's push-out (ContactImpulses::kPushOutSpeed), m/s.
  double driveSpeed() const { return drive_speed_; }
  /// The most energy body b could have after the step: its energy before, plus each node's
  /// impulse in the step (with any move its velocity does not account for, as the momentum that
  /// would have made it) times the most speed that impulse could have worked at (the
  /// node's own at the start, the drive speed, and what its loads and gravity add in dt). J.
  double bound(const Body& body, int b, double dt) const;
  /// Body b's energy now, kinetic and elastic (a linear finite-element body's 1/2 u^T K u, the
  /// energy its step conserves), J.
  double energy(const Body& body, int b);
  /// Whether body b's energy, kinetic and elastic, leapt past kLeap times its bound. A step that
  /// did not leap is remembered: the next before() takes its energy from here.
  bool leapt(const Body& body, int b, double dt);

 private:
  /// Adds the speeds of held nodes after the step to driveSpeed().
  void heldNodes(const BodyList& bodies);
  /// The fastest a point of an obstacle within the bodies' bounding box moves from its pose of
  /// the last step to its present one, m/s; zero for obstacles other than the last step's.
  double obstacleSpeed(const BodyList& bodies, const std::vector<PlacedShape>& obstacles,
                       double dt) const;

  std::vector<Eigen::VectorXd> start_velocities_, start_positions_;  ///< per body, 3n
  std::vector<double> start_energies_;  ///< per body, kinetic + elastic, J
  /// Per body, the last state leapt() passed: positions, velocities, energy; and whether one is
  /// there (judged_ non-zero).
  std::vector<Eigen::VectorXd> end_positions_, end_velocities_;
  std::vector<double> end_energies_;
  std::vector<char> judged_;
  std::vector<Eigen::VectorXd> forces_;            ///< per body, 3n: a linear body's K (x - x0)
  std::vector<Eigen::Isometry3d> obstacle_poses_;  ///< in the last step
  double drive_speed_ = 0.0;
};

}  // namespace deformable_sim::core
