#include "deformable_sim/core/elements/plasticity.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "deformable_sim/core/elements/cell.h"
#include "deformable_sim/core/elements/tetrahedron.h"

namespace deformable_sim::core {

void validate(const PlasticitySettings& settings) {
  auto check = [](double value, bool ok, const char* name, const char* rule) {
    if (!std::isfinite(value) || !ok) {
      throw std::invalid_argument(std::string("plasticity: ") + name + " = " +
                                  std::to_string(value) + " (must be finite and " + rule + ")");
    }
  };
  check(settings.yield, settings.yield >= 0.0, "yield", ">= 0");
  check(settings.creep, settings.creep >= 0.0, "creep", ">= 0");
  check(settings.max_strain, settings.max_strain > 0.0, "max_strain", "> 0");
}

Plasticity::Plasticity(const Mesh& mesh, const PlasticitySettings& settings)
    : settings_(settings), plastic_strains_(mesh.numElements(), Eigen::Matrix3d::Zero()) {
  validate(settings);
}

Eigen::Matrix3d Plasticity::flow(int e, const Eigen::Matrix3d& f, const Eigen::Matrix3d& r,
                                 double lambda, double mu, double dt) {
  const Eigen::Matrix3d unrotated = r.transpose() * f;
  const Eigen::Matrix3d total =
      0.5 * (unrotated + unrotated.transpose()) - Eigen::Matrix3d::Identity();
  Eigen::Matrix3d& plastic = plastic_strains_[e];
  const Eigen::Matrix3d elastic = total - plastic;
  // A non-finite state (which the watchdog undoes) must not reach the plastic memory.
  if (elastic.allFinite() && elastic.norm() > settings_.yield) {
    // Implicit in the creep rate so that a large rate times dt never overshoots the elastic strain.
    plastic += std::min(settings_.creep * dt, 1.0) * elastic;
    const double norm = plastic.norm();
    if (norm > settings_.max_strain) plastic *= settings_.max_strain / norm;
    ++flowing_;
  }
  return lambda * plastic.trace() * Eigen::Matrix3d::Identity() + 2.0 * mu * plastic;
}

void Plasticity::step(const Mesh& mesh, const CorotationalElasticity& elasticity,
                      const Eigen::VectorXd& x, double dt, Eigen::VectorXd& forces) {
  forces.setZero();
  flowing_ = 0;
  const double lambda = elasticity.lambda(), mu = elasticity.mu();
  const std::vector<Eigen::Matrix3d>& rotations = elasticity.rotations();
  const std::vector<TetrahedronRest>& rest = elasticity.restData();
  for (int e = 0; e < mesh.numTetrahedra(); ++e) {
    const Tetrahedron& t = mesh.tetrahedra[e];
    const Eigen::Matrix3d f =
        deformationGradient(rest[e], x.segment<3>(3 * t[0]), x.segment<3>(3 * t[1]),
                            x.segment<3>(3 * t[2]), x.segment<3>(3 * t[3]));
    const Eigen::Matrix3d stress = flow(e, f, rotations[e], lambda, mu, dt);
    if (stress.isZero(0.0)) continue;
    const Eigen::Matrix3d rotated_stress = rest[e].volume * rotations[e] * stress;
    for (int a = 0; a < 4; ++a)
      forces.segment<3>(3 * t[a]) += rotated_stress * rest[e].gradients[a];
  }
  // Cells: strain and forces from the centre (one-point), consistent with their rotation.
  for (int c = 0; c < static_cast<int>(mesh.cells.size()); ++c) {
    const Cell& cell = mesh.cells[c];
    const CellRest& cell_rest = elasticity.cellRestData(c);
    CellVectors corners;
    for (int k = 0; k < cell.size(); ++k) corners[k] = x.segment<3>(3 * cell.nodes[k]);
    const int e = mesh.numTetrahedra() + c;
    const Eigen::Matrix3d stress = flow(e, cellDeformationGradient(cell_rest, cell.size(), corners),
                                        rotations[e], lambda, mu, dt);
    if (stress.isZero(0.0)) continue;
    const Eigen::Matrix3d rotated_stress =
        mesh.cellFraction(c) * cell_rest.volume * rotations[e] * stress;
    for (int k = 0; k < cell.size(); ++k) {
      forces.segment<3>(3 * cell.nodes[k]) += rotated_stress * cell_rest.centre_gradients[k];
    }
  }
}

}  // namespace deformable_sim::core
