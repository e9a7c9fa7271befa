// Simulations for the core's tests, built as io::buildSimulation would but without io: every
// body of these specs has a generated box mesh.
#pragma once

#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/session/default_scene.h"
#include "deformable_sim/core/session/scene.h"
#include "deformable_sim/core/session/simulation.h"
#include "deformable_sim/core/surface_bodies/surface_body.h"
#include "scene_builder.h"

namespace deformable_sim::test {

/// The simulation of `spec`, each body's mesh made from its box_mesh (which each must have).
/// The material law a test binary runs its scenes with: DEFORMABLE_SIM_TEST_LAW=neo_hookean
/// puts every body of the warped stiffness on Neo-Hookean (CMake runs test_core_body so, as
/// test_core_body_neo_hookean); unset, scenes keep their own.
inline void applyLawUnderTest(core::SceneSpec& spec) {
  const char* law = std::getenv("DEFORMABLE_SIM_TEST_LAW");
  if (!law || std::string(law) != "neo_hookean") return;
  for (core::BodySpec& body : spec.bodies) body.material.law = core::ElasticLaw::kNeoHookean;
}

inline core::Simulation boxMeshSimulation(core::SceneSpec spec) {
  applyLawUnderTest(spec);
  std::vector<core::Mesh> meshes;
  for (const core::BodySpec& body : spec.bodies) {
    const core::BoxMeshSpec& box = *body.box_mesh;
    meshes.push_back(core::makeBoxMesh(box.min, box.max, box.cells, box.element));
  }
  return core::Simulation(spec, std::move(meshes));
}

/// The simulation of `spec` whose first bodies are made from the surfaces of `made` (their grids,
/// their surfaces embedded), the rest from their box_mesh.
inline core::Simulation surfaceSimulation(const core::SceneSpec& spec,
                                          std::vector<core::SurfaceBody> made) {
  std::vector<core::Mesh> meshes;
  for (const core::SurfaceBody& body : made) meshes.push_back(body.voxels.mesh);
  for (size_t b = made.size(); b < spec.bodies.size(); ++b) {
    const core::BoxMeshSpec& box = *spec.bodies[b].box_mesh;
    meshes.push_back(core::makeBoxMesh(box.min, box.max, box.cells, box.element));
  }
  core::Simulation sim(spec, std::move(meshes));
  for (size_t b = 0; b < made.size(); ++b) {
    sim.setEmbeddedSurface(static_cast<int>(b), std::move(made[b].surface));
  }
  return sim;
}

/// Selects the nodes whose rest positions lie in the box [min, max].
inline core::NodeSelection boxSelection(const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
  core::NodeSelection selection;
  selection.kind = core::NodeSelection::Kind::kBox;
  selection.box = {min, max};
  return selection;
}

/// A scene with no body yet: gravity, warping, contact (friction 0.5; between bodies if
/// `bodies`) and a 1 m x 1 m floor 10 cm thick whose top is at z = 0, 0.01 s steps.
inline core::SceneSpec sceneOnAFloor(bool bodies) {
  return SceneBuilder().dt(0.01).gravity(9.81).warped().contact(0.5, bodies).floor({1, 1, 0.1});
}

/// The built-in default scene, runnable.
inline core::Simulation defaultSimulation() { return boxMeshSimulation(core::defaultScene()); }

}  // namespace deformable_sim::test
