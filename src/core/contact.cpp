#include "deformable_sim/core/contact.h"

namespace deformable_sim::core {

int resolveContacts(FemBody& body, const std::vector<PlacedShape>& obstacles,
                    const ContactSettings& settings) {
  Eigen::VectorXd& x = body.mutablePositions();
  Eigen::VectorXd& v = body.mutableVelocities();
  int contacts = 0;
  for (const PlacedShape& obstacle : obstacles) {
    const Eigen::Isometry3d to_shape = obstacle.pose.inverse();
    for (int i = 0; i < body.numNodes(); ++i) {
      if (body.isConstrained(i)) continue;
      Eigen::Vector3d surface, normal;
      const Eigen::Vector3d p = x.segment<3>(3 * i);
      if (!(signedDistance(obstacle.shape, to_shape * p, &surface, &normal) < 0.0)) continue;
      ++contacts;
      x.segment<3>(3 * i) = obstacle.pose * surface;
      const Eigen::Vector3d n = obstacle.pose.linear() * normal;
      Eigen::Vector3d velocity = v.segment<3>(3 * i);
      const double into = -velocity.dot(n);
      if (into <= 0.0) continue;  // already leaving
      velocity += into * n;
      if (settings.friction > 0.0) {
        const double sliding = velocity.norm();
        const double slowed = settings.friction * into;
        velocity = sliding <= slowed ? Eigen::Vector3d::Zero()
                                     : Eigen::Vector3d(velocity * (1.0 - slowed / sliding));
      }
      v.segment<3>(3 * i) = velocity;
    }
  }
  return contacts;
}

}  // namespace deformable_sim::core
