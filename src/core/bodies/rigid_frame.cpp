#include "deformable_sim/core/bodies/rigid_frame.h"

#include "deformable_sim/core/base/rotation.h"

namespace deformable_sim::core {

RigidFrame bestFitFrame(const Eigen::VectorXd& x, const Eigen::VectorXd& x0,
                        const std::vector<double>& masses, const std::vector<int>& nodes) {
  const int count =
      nodes.empty() ? static_cast<int>(masses.size()) : static_cast<int>(nodes.size());
  auto node = [&](int k) { return nodes.empty() ? k : nodes[k]; };
  RigidFrame frame;
  double total = 0.0;
  for (int k = 0; k < count; ++k) {
    const int i = node(k);
    total += masses[i];
    frame.origin += masses[i] * x.segment<3>(3 * i);
    frame.rest_origin += masses[i] * x0.segment<3>(3 * i);
  }
  if (!(total > 0.0)) return frame;
  frame.origin /= total;
  frame.rest_origin /= total;
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  for (int k = 0; k < count; ++k) {
    const int i = node(k);
    a += masses[i] * (x.segment<3>(3 * i) - frame.origin) *
         (x0.segment<3>(3 * i) - frame.rest_origin).transpose();
  }
  frame.rotation = extractRotation(a);
  return frame;
}

}  // namespace deformable_sim::core
