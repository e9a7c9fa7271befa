// Mass, centre of mass and second moment of a mesh's volume, integrated element by element: what
// a rigid or pseudo-rigid body needs from its mesh.
#pragma once

#include <Eigen/Core>

#include "deformable_sim/core/elements/mesh.h"

namespace deformable_sim::core {

struct MassProperties {
  double volume = 0.0;                               ///< m^3
  double mass = 0.0;                                 ///< kg
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< rest centre of mass, m
  /// Euler tensor about the centre, E = integral of rho a a^T dV with a = X - centre, kg m^2.
  Eigen::Matrix3d second_moment = Eigen::Matrix3d::Zero();

  /// The inertia tensor about the centre, tr(E) I - E, kg m^2.
  Eigen::Matrix3d inertia() const {
    return second_moment.trace() * Eigen::Matrix3d::Identity() - second_moment;
  }
};

/// Exact for tetrahedra and for undistorted (affine) cells; the cells' Gauss rules otherwise.
MassProperties massProperties(const Mesh& mesh, double density);

}  // namespace deformable_sim::core
