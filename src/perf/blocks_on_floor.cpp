#include "deformable_sim/perf/blocks_on_floor.h"

#include <string>
#include <utility>
#include <vector>

#include "deformable_sim/core/elements/box_mesh.h"

namespace deformable_sim::perf {

core::Simulation makeBlocksOnFloor(const BlocksOnFloor& scene) {
  core::SceneSpec spec;
  spec.dt = 0.01;
  spec.effects.gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
  spec.effects.warping = true;
  spec.effects.damping = core::RayleighDamping{1.0, 0.002};
  spec.solver.threads = scene.threads;
  if (scene.direct) spec.solver.method = core::SolverSettings::Method::kDirect;
  if (scene.floor) {
    spec.contact = core::ContactSettings{0.5, scene.bodies, scene.self};
    core::PlacedShape floor;
    floor.name = "floor";
    floor.shape.size = Eigen::Vector3d(4.0, 4.0, 0.2);
    floor.pose.translation() = Eigen::Vector3d(0.0, 0.0, -0.1);  // top at z = 0
    spec.obstacles.push_back(floor);
  }
  std::vector<core::Mesh> meshes;
  for (int b = 0; b < scene.count; ++b) {
    core::BodySpec block;
    block.name = "block" + std::to_string(b);
    const Eigen::Vector3d min(0.08 * b, 0.0, 0.0);
    block.box_mesh = core::BoxMeshSpec{min, min + Eigen::Vector3d(0.08, 0.08, 0.04), {8, 8, 4}};
    block.material = {1.0e5, 0.3, 500.0};
    if (!scene.floor) {
      core::NodeSelection clamp;
      clamp.kind = core::NodeSelection::Kind::kBox;
      clamp.box = {min - Eigen::Vector3d(1e-6, 1.0, 1.0), min + Eigen::Vector3d(1e-6, 1.0, 1.0)};
      block.fixed.push_back(clamp);
    }
    meshes.push_back(core::makeBoxMesh(block.box_mesh->min, block.box_mesh->max,
                                       block.box_mesh->cells, block.box_mesh->element));
    spec.bodies.push_back(std::move(block));
  }
  return core::Simulation(spec, std::move(meshes));
}

}  // namespace deformable_sim::perf
