// Turning distributed and resultant loads into nodal forces.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "deformable_sim/core/elements/mesh.h"

namespace deformable_sim::core {

/// Adds to f (3n, N) the consistent nodal loads of a uniform traction (Pa) on every boundary face
/// whose nodes are all in `selected` (node indices): the traction times the integral of each
/// node's shape function over the face (a third of a triangle's area; a quarter of a
/// parallelogram's). Returns the loaded area, m^2 (0: no face).
double addTractionLoad(const Mesh& mesh, const std::vector<Face>& boundary,
                       const std::vector<int>& selected, const Eigen::Vector3d& traction,
                       Eigen::VectorXd& f);

/// Adds to f the force `total` (N) split equally among the selected nodes (at least one).
void addTotalForce(const std::vector<int>& selected, const Eigen::Vector3d& total,
                   Eigen::VectorXd& f);

}  // namespace deformable_sim::core
