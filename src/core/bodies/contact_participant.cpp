#include "deformable_sim/core/bodies/contact_participant.h"

namespace deformable_sim::core {

Eigen::Matrix3d ContactParticipant::compliance(const SurfacePoint& point, bool, int) const {
  return complianceFromInverseMass(point);
}

Eigen::Matrix3d ContactParticipant::complianceFromInverseMass(const SurfacePoint& point) const {
  Eigen::Matrix3d w;
  for (int a = 0; a < 3; ++a) w(a, a) = inverseMass(point, Eigen::Vector3d::Unit(a));
  for (int a = 0; a < 3; ++a) {
    for (int b = a + 1; b < 3; ++b) {
      const Eigen::Vector3d both = Eigen::Vector3d::Unit(a) + Eigen::Vector3d::Unit(b);
      w(a, b) = w(b, a) = 0.5 * (inverseMass(point, both) - w(a, a) - w(b, b));
    }
  }
  return w;
}

}  // namespace deformable_sim::core
