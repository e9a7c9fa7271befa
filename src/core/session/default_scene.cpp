#include "deformable_sim/core/session/default_scene.h"

namespace deformable_sim::core {

SceneSpec defaultScene() {
  SceneSpec scene;
  scene.dt = 0.01;
  scene.effects.gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
  scene.effects.warping = true;
  scene.effects.damping = RayleighDamping{1.0, 0.002};
  // Ten times looser than the library's default: a pushed session stays as close to a direct
  // solve's trajectory as matters next to the mesh's own error, for fewer iterations a step
  // (measured in doc/performance.md, replay section).
  scene.solver.tolerance = 1.0e-5;

  BodySpec beam;
  beam.name = "beam";
  beam.box_mesh = BoxMeshSpec{{0.0, -0.05, -0.05}, {0.5, 0.05, 0.05}, {16, 4, 4}};
  beam.material = {1.0e5, 0.3, 100.0};
  NodeSelection clamp;
  clamp.kind = NodeSelection::Kind::kBox;
  clamp.box = {{-1e-6, -1.0, -1.0}, {1e-6, 1.0, 1.0}};
  beam.fixed.push_back(clamp);
  NodeSelection tip;
  tip.kind = NodeSelection::Kind::kBox;
  tip.box = {{0.5 - 1e-6, -1.0, -1.0}, {0.5 + 1e-6, 1.0, 1.0}};
  beam.groups["tip"] = tip;
  beam.wrench_radius = 0.05;
  scene.bodies.push_back(beam);
  return scene;
}

}  // namespace deformable_sim::core
