#include "deformable_sim/core/outputs/strain.h"

#include <algorithm>
#include <array>

#include "deformable_sim/core/base/rotation.h"
#include "deformable_sim/core/bodies/finite_element_body.h"
#include "deformable_sim/core/elements/cell.h"
#include "deformable_sim/core/elements/tetrahedron.h"

namespace deformable_sim::core {

namespace {

// |sym(R^T F) - I|: the rotation-free (small-strain) measure of F with its rotation R.
double strainMagnitude(const Eigen::Matrix3d& f, const Eigen::Matrix3d& r) {
  const Eigen::Matrix3d unrotated = r.transpose() * f;
  return (0.5 * (unrotated + unrotated.transpose()) - Eigen::Matrix3d::Identity()).norm();
}

double strainMagnitude(const Eigen::Matrix3d& f) { return strainMagnitude(f, extractRotation(f)); }

// A rigid or pseudo-rigid body deforms homogeneously: the strain of one element is everywhere's.
double homogeneousStrain(const Body& body) {
  const Mesh& mesh = body.mesh();
  const Eigen::VectorXd& x = body.positions();
  if (!mesh.tetrahedra.empty()) {
    const Tetrahedron& t = mesh.tetrahedra.front();
    const TetrahedronRest rest = computeTetrahedronRest(
        {mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]], mesh.positions[t[3]]});
    return strainMagnitude(deformationGradient(rest, x.segment<3>(3 * t[0]), x.segment<3>(3 * t[1]),
                                               x.segment<3>(3 * t[2]), x.segment<3>(3 * t[3])));
  }
  const Cell& cell = mesh.cells.front();
  CellVectors corners;
  for (int k = 0; k < cell.size(); ++k) corners[k] = x.segment<3>(3 * cell.nodes[k]);
  const CellRest rest = computeCellRest(cell.type, cellCorners(cell, mesh.positions));
  return strainMagnitude(cellDeformationGradient(rest, cell.size(), corners));
}

}  // namespace

void nodalStrain(const Body& body, std::vector<double>& strain) {
  const FiniteElementBody* elements = body.finiteElements();
  if (!elements) {
    strain.assign(body.numNodes(), homogeneousStrain(body));
    return;
  }
  strain.assign(body.numNodes(), 0.0);
  const Eigen::VectorXd& x = body.positions();
  const ElasticModel& elasticity = elements->elasticity();
  const std::vector<Tetrahedron>& tetrahedra = body.mesh().tetrahedra;
  // Tetrahedra a batch of rotations at a time.
  const int num_tetrahedra = static_cast<int>(tetrahedra.size());
  for (int first = 0; first < num_tetrahedra; first += kRotationBatch) {
    const int count = std::min(kRotationBatch, num_tetrahedra - first);
    std::array<Eigen::Matrix3d, kRotationBatch> f, r;
    for (int k = 0; k < count; ++k) f[k] = elasticity.deformationGradient(first + k, x);
    extractRotations(f.data(), r.data(), count);
    for (int k = 0; k < count; ++k) {
      const double magnitude = strainMagnitude(f[k], r[k]);
      for (int i : tetrahedra[first + k]) strain[i] = std::max(strain[i], magnitude);
    }
  }
  // Cells: the strain where the elasticity takes their deformation gradient.
  const std::vector<Cell>& cells = body.mesh().cells;
  for (size_t c = 0; c < cells.size(); ++c) {
    const Cell& cell = cells[c];
    const double magnitude =
        strainMagnitude(elasticity.deformationGradient(num_tetrahedra + static_cast<int>(c), x));
    for (int k = 0; k < cell.size(); ++k) {
      strain[cell.nodes[k]] = std::max(strain[cell.nodes[k]], magnitude);
    }
  }
}

}  // namespace deformable_sim::core
