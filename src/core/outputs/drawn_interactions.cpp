#include "deformable_sim/core/outputs/drawn_interactions.h"

namespace deformable_sim::core {

namespace {

DrawnNodes drawnNodes(const Body& body, int index, const CommandProcessor& commands) {
  const Eigen::VectorXd& x = body.positions();
  DrawnNodes drawn;
  std::vector<bool> grasped(body.numNodes(), false);
  for (const auto& [name, grasp] : commands.grasps()) {
    if (grasp.body != index) continue;
    for (int i : grasp.nodes) {
      grasped[i] = true;
      drawn.grasped.push_back(x.segment<3>(3 * i));
    }
  }
  for (int i = 0; i < body.numNodes(); ++i) {
    if (body.isConstrained(i) && !grasped[i]) drawn.fixed.push_back(x.segment<3>(3 * i));
  }
  for (const auto& [name, nodes] : body.mesh().groups) {
    std::vector<Eigen::Vector3d> points;
    for (int i : nodes) points.push_back(x.segment<3>(3 * i));
    drawn.groups.emplace_back(name, std::move(points));
  }
  return drawn;
}

}  // namespace

DrawnInteractions drawnInteractions(const BodyList& bodies, const CommandProcessor& commands,
                                    double metres_per_newton) {
  DrawnInteractions drawn;
  for (size_t b = 0; b < bodies.size(); ++b) {
    drawn.bodies.push_back(drawnNodes(bodies[b], static_cast<int>(b), commands));
  }
  for (const auto& [source, wrench] : commands.activeWrenches()) {
    if (wrench.force.isZero(0.0)) continue;
    drawn.wrenches.push_back({wrench.point, wrench.point + metres_per_newton * wrench.force});
  }
  return drawn;
}

}  // namespace deformable_sim::core
