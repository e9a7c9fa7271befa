// What the property tests of the elements (the tetrahedron's, the other cells') share: stacked
// node positions and the elastic force at them.
#pragma once

#include <Eigen/Core>

#include "deformable_sim/core/elements/corotational_elasticity.h"
#include "deformable_sim/core/elements/mesh.h"

namespace deformable_sim::test {

/// The mesh's rest positions as one 3n vector.
inline Eigen::VectorXd stacked(const core::Mesh& mesh) {
  Eigen::VectorXd x(3 * mesh.numNodes());
  for (int i = 0; i < mesh.numNodes(); ++i) x.segment<3>(3 * i) = mesh.positions[i];
  return x;
}

/// Elastic force f = -(K' x + f0') after updating the rotations at x.
inline Eigen::VectorXd elasticForce(core::CorotationalElasticity& elasticity,
                                    const Eigen::VectorXd& x, bool warping) {
  elasticity.update(x, warping);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(x.size());
  Eigen::VectorXd scratch(x.size());
  elasticity.addElasticForces(x, f, scratch);
  return f;
}

}  // namespace deformable_sim::test
