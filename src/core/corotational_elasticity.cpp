#include "deformable_sim/core/corotational_elasticity.h"

#include <Eigen/LU>

#include "deformable_sim/core/rotation.h"

namespace deformable_sim::core {

CorotationalElasticity::CorotationalElasticity(const Mesh& mesh,
                                               const LinearElasticMaterial& material)
    : tetrahedra_(mesh.tetrahedra),
      rest_positions_(3 * mesh.numNodes()),
      rotations_(mesh.tetrahedra.size(), Eigen::Matrix3d::Identity()),
      stiffness_(mesh.numNodes(), mesh.tetrahedra),
      force_offset_(Eigen::VectorXd::Zero(3 * mesh.numNodes())) {
  validate(material);
  for (int i = 0; i < mesh.numNodes(); ++i) rest_positions_.segment<3>(3 * i) = mesh.positions[i];
  rest_.reserve(tetrahedra_.size());
  block_index_.reserve(tetrahedra_.size());
  for (const Tetrahedron& t : tetrahedra_) {
    rest_.push_back(computeTetrahedronRest(
        {mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]], mesh.positions[t[3]]},
        material));
    std::array<int, 16> slots;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) slots[4 * i + j] = stiffness_.blockIndex(t[i], t[j]);
    }
    block_index_.push_back(slots);
  }
}

void CorotationalElasticity::setMaterial(const Mesh& mesh, const LinearElasticMaterial& material) {
  validate(material);
  for (size_t e = 0; e < tetrahedra_.size(); ++e) {
    const Tetrahedron& t = tetrahedra_[e];
    rest_[e] = computeTetrahedronRest(
        {mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]], mesh.positions[t[3]]},
        material);
  }
}

int CorotationalElasticity::update(const Eigen::VectorXd& x, bool warping) {
  stiffness_.setZero();
  force_offset_.setZero();
  std::vector<Eigen::Matrix3d>& blocks = stiffness_.blocks();
  int inverted = 0;
  for (size_t e = 0; e < tetrahedra_.size(); ++e) {
    const Tetrahedron& t = tetrahedra_[e];
    const TetrahedronRest& rest = rest_[e];
    if (warping) {
      const Eigen::Matrix3d f =
          deformationGradient(rest, x.segment<3>(3 * t[0]), x.segment<3>(3 * t[1]),
                              x.segment<3>(3 * t[2]), x.segment<3>(3 * t[3]));
      if (!(f.determinant() > 0.0)) ++inverted;
      rotations_[e] = extractRotation(f);
    }
    const Eigen::Matrix3d& r = rotations_[e];
    for (int i = 0; i < 4; ++i) {
      Eigen::Vector3d rest_force = Eigen::Vector3d::Zero();
      for (int j = 0; j < 4; ++j) {
        const Eigen::Matrix3d& k_ij = rest.stiffness[i][j];
        rest_force.noalias() += k_ij * rest_positions_.segment<3>(3 * t[j]);
        if (j < i) continue;  // K'_ji = K'_ij^T: compute each pair once
        const Eigen::Matrix3d warped = r * k_ij * r.transpose();
        blocks[block_index_[e][4 * i + j]] += warped;
        if (j > i) blocks[block_index_[e][4 * j + i]] += warped.transpose();
      }
      force_offset_.segment<3>(3 * t[i]).noalias() -= r * rest_force;
    }
  }
  return inverted;
}

void CorotationalElasticity::addElasticForces(const Eigen::VectorXd& x, Eigen::VectorXd& f,
                                              Eigen::VectorXd& scratch) const {
  stiffness_.multiply(x, scratch);
  f -= scratch + force_offset_;
}

double CorotationalElasticity::elasticEnergy(const Eigen::VectorXd& x) const {
  double energy = 0.0;
  for (size_t e = 0; e < tetrahedra_.size(); ++e) {
    const Tetrahedron& t = tetrahedra_[e];
    Eigen::Matrix<double, 12, 1> u;
    for (int i = 0; i < 4; ++i) {
      u.segment<3>(3 * i) =
          rotations_[e].transpose() * x.segment<3>(3 * t[i]) - rest_positions_.segment<3>(3 * t[i]);
    }
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        energy += 0.5 * u.segment<3>(3 * i).dot(rest_.at(e).stiffness[i][j] * u.segment<3>(3 * j));
      }
    }
  }
  return energy;
}

}  // namespace deformable_sim::core
