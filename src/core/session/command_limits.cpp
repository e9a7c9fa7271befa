#include "deformable_sim/core/session/command_limits.h"

#include <numeric>

namespace deformable_sim::core {

WrenchBounds wrenchBounds(const Body& body, const CommandLimits& limits) {
  constexpr double kStandardGravity = 9.81;  // m/s^2: a weight even in a scene without gravity
  WrenchBounds bounds;
  if (limits.max_force > 0.0) {
    bounds.force = limits.max_force;
  } else {
    const std::vector<double>& masses = body.nodalMasses();
    const double mass = std::accumulate(masses.begin(), masses.end(), 0.0);
    bounds.force = kWeightsPerWrench * mass * kStandardGravity;
  }
  if (limits.max_torque > 0.0) {
    bounds.torque = limits.max_torque;
  } else {
    const Eigen::Map<const Eigen::Matrix3Xd> rest(body.restPositions().data(), 3, body.numNodes());
    const double size = body.numNodes() > 0
                            ? (rest.rowwise().maxCoeff() - rest.rowwise().minCoeff()).maxCoeff()
                            : 0.0;
    bounds.torque = bounds.force * size;
  }
  return bounds;
}

}  // namespace deformable_sim::core
