// What the tests measure of a body's nodes: mass, centres, momentum. Written once so that every
// test measures the same way.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "deformable_sim/core/bodies/body_list.h"

namespace deformable_sim::test {

/// The sum of the nodal masses, kg.
inline double totalMass(const core::Body& body) {
  double total = 0.0;
  for (double m : body.nodalMasses()) total += m;
  return total;
}

/// The mass-weighted mean of the node positions, m.
inline Eigen::Vector3d centreOfMass(const core::Body& body) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int i = 0; i < body.numNodes(); ++i) {
    c += body.nodalMasses()[i] * body.positions().segment<3>(3 * i);
  }
  return c / totalMass(body);
}

/// The plain mean of the node positions, m: the centre of the grid, whatever its masses.
inline Eigen::Vector3d centreOfNodes(const core::Body& body) {
  return body.positions().reshaped(3, body.numNodes()).rowwise().mean();
}

/// Linear momentum of a body, N s.
inline Eigen::Vector3d momentum(const core::Body& body) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int i = 0; i < body.numNodes(); ++i) {
    p += body.nodalMasses()[i] * body.velocities().segment<3>(3 * i);
  }
  return p;
}

/// Total linear momentum of the bodies, N s.
inline Eigen::Vector3d totalMomentum(const core::BodyList& bodies) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (const core::Body& body : bodies) p += momentum(body);
  return p;
}

}  // namespace deformable_sim::test
