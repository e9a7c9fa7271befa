#include "deformable_sim/perf/cantilever.h"

#include "deformable_sim/core/elements/box_mesh.h"

namespace deformable_sim::perf {

Cantilever makeCantilever(const Eigen::Vector3i& cells) {
  Cantilever c;
  c.mesh = core::makeBoxMesh({0.0, -0.1, -0.1}, {0.6, 0.1, 0.1}, cells);
  for (int i = 0; i < c.mesh.numNodes(); ++i) {
    if (c.mesh.positions[i].x() < 1e-9) c.clamped.push_back(i);
  }
  c.effects.warping = true;
  c.effects.gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
  c.solver.tolerance = 1e-6;
  c.solver.max_iterations = 1000;
  return c;
}

core::FiniteElementBody makeCantileverBody(const Cantilever& cantilever) {
  core::FiniteElementBody body("cantilever", cantilever.mesh, cantilever.material,
                               cantilever.effects, cantilever.solver);
  body.fixNodes(cantilever.clamped);
  return body;
}

}  // namespace deformable_sim::perf
