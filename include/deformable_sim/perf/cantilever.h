// The performance benchmark's scene: a soft cantilever (0.6 x 0.2 x 0.2 m, E = 1 MPa, nu = 0.3,
// 1000 kg/m^3) clamped at x = 0 and swinging under gravity, stepped at dt = 0.01 s with CG to a
// relative residual of 1e-6 — the same scene for every mesh size, and for the peer.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "deformable_sim/core/bodies/finite_element_body.h"

namespace deformable_sim::perf {

struct Cantilever {
  core::Mesh mesh;
  core::LinearElasticMaterial material{1.0e6, 0.3, 1000.0};
  std::vector<int> clamped;  ///< nodes at x = 0
  core::BodyEffects effects;
  core::SolverSettings solver;
  double dt = 0.01;
};

/// The cantilever cut into cells[0] x cells[1] x cells[2] boxes of six tetrahedra each.
Cantilever makeCantilever(const Eigen::Vector3i& cells);

/// A body of the cantilever with its clamp applied, at rest.
core::FiniteElementBody makeCantileverBody(const Cantilever& cantilever);

}  // namespace deformable_sim::perf
