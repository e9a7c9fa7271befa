#include "deformable_sim/core/corotational_elasticity.h"

#include <Eigen/LU>
#include <algorithm>
#include <bitset>
#include <numeric>

#include "deformable_sim/core/parallel_for.h"
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
        {mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]], mesh.positions[t[3]]}));
    std::array<int, 16> slots;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) slots[4 * i + j] = stiffness_.blockIndex(t[i], t[j]);
    }
    block_index_.push_back(slots);
  }
  lambda_ = lameLambda(material);
  mu_ = lameMu(material);
  setRestForces();
  colourElements(mesh.numNodes());
}

void CorotationalElasticity::colourElements(int num_nodes) {
  // Greedy: each element takes the lowest colour none of its nodes' elements has yet.
  constexpr int kMaxColours = 256;
  std::vector<std::bitset<kMaxColours>> used(num_nodes);
  std::vector<int> colour(tetrahedra_.size());
  int num_colours = 0;
  for (size_t e = 0; e < tetrahedra_.size(); ++e) {
    const Tetrahedron& t = tetrahedra_[e];
    const std::bitset<kMaxColours> taken = used[t[0]] | used[t[1]] | used[t[2]] | used[t[3]];
    int c = 0;
    while (c < kMaxColours && taken[c]) ++c;
    if (c == kMaxColours) {  // a node in hundreds of elements: one colour each, no parallelism
      coloured_elements_.resize(tetrahedra_.size());
      std::iota(coloured_elements_.begin(), coloured_elements_.end(), 0);
      colour_start_.resize(tetrahedra_.size() + 1);
      std::iota(colour_start_.begin(), colour_start_.end(), 0);
      return;
    }
    for (int i : t) used[i].set(c);
    colour[e] = c;
    num_colours = std::max(num_colours, c + 1);
  }
  colour_start_.assign(num_colours + 1, 0);
  for (int c : colour) ++colour_start_[c + 1];
  for (int c = 0; c < num_colours; ++c) colour_start_[c + 1] += colour_start_[c];
  coloured_elements_.resize(tetrahedra_.size());
  std::vector<int> next(colour_start_.begin(), colour_start_.end() - 1);
  for (size_t e = 0; e < tetrahedra_.size(); ++e) coloured_elements_[next[colour[e]]++] = e;
}

void CorotationalElasticity::setMaterial(const LinearElasticMaterial& material) {
  validate(material);
  lambda_ = lameLambda(material);
  mu_ = lameMu(material);
  setRestForces();
}

void CorotationalElasticity::setRestForces() {
  rest_forces_.resize(tetrahedra_.size());
  for (size_t e = 0; e < tetrahedra_.size(); ++e) {
    const Tetrahedron& t = tetrahedra_[e];
    const TetrahedronRest& rest = rest_[e];
    for (int i = 0; i < 4; ++i) {
      Eigen::Vector3d force = Eigen::Vector3d::Zero();
      for (int j = 0; j < 4; ++j) {
        force += stiffnessBlock(lambda_ * rest.volume, mu_ * rest.volume, rest.gradients[i],
                                rest.gradients[j]) *
                 rest_positions_.segment<3>(3 * t[j]);
      }
      rest_forces_[e][i] = force;
    }
  }
}

int CorotationalElasticity::update(const Eigen::VectorXd& x, bool warping) {
  const int inverted = warping ? updateRotations(x) : 0;
  if (!warping) {
    for (Eigen::Matrix3d& r : rotations_) r.setIdentity();
  }
  assemble();
  return inverted;
}

int CorotationalElasticity::updateRotations(const Eigen::VectorXd& x) {
  return parallelCount(threads_, 0, static_cast<int>(tetrahedra_.size()), [&](int e) {
    const Tetrahedron& t = tetrahedra_[e];
    const Eigen::Matrix3d f =
        deformationGradient(rest_[e], x.segment<3>(3 * t[0]), x.segment<3>(3 * t[1]),
                            x.segment<3>(3 * t[2]), x.segment<3>(3 * t[3]));
    rotations_[e] = extractRotation(f);
    return f.determinant() > 0.0 ? 0 : 1;
  });
}

void CorotationalElasticity::assemble() {
  stiffness_.setZero();
  force_offset_.setZero();
  if (threads_ <= 1) {
    // Element order: neighbouring elements share blocks, which stay in cache.
    for (int e = 0; e < static_cast<int>(tetrahedra_.size()); ++e) addElement(e);
    return;
  }
  // Colour by colour: the elements of a colour touch disjoint blocks, and every block sums its
  // elements in colour order, the same for any number of threads above one.
  const int num_colours = static_cast<int>(colour_start_.size()) - 1;
#pragma omp parallel num_threads(threads_)
  for (int c = 0; c < num_colours; ++c) {
#pragma omp for schedule(static)
    for (int k = colour_start_[c]; k < colour_start_[c + 1]; ++k) addElement(coloured_elements_[k]);
  }
}

void CorotationalElasticity::addElement(int e) {
  std::vector<Eigen::Matrix3d>& blocks = stiffness_.blocks();
  const Tetrahedron& t = tetrahedra_[e];
  const TetrahedronRest& rest = rest_[e];
  const Eigen::Matrix3d& r = rotations_[e];
  const double lambda_volume = lambda_ * rest.volume, mu_volume = mu_ * rest.volume;
  std::array<Eigen::Vector3d, 4> g;  // R grad N_i: R Ke_ij R^T is Ke_ij of these
  for (int i = 0; i < 4; ++i) g[i].noalias() = r * rest.gradients[i];
  const std::array<int, 16>& slot = block_index_[e];
  for (int i = 0; i < 4; ++i) {
    blocks[slot[5 * i]] += stiffnessBlock(lambda_volume, mu_volume, g[i], g[i]);
    for (int j = i + 1; j < 4; ++j) {  // K'_ji = K'_ij^T: compute each pair once
      const Eigen::Matrix3d warped = stiffnessBlock(lambda_volume, mu_volume, g[i], g[j]);
      blocks[slot[4 * i + j]] += warped;
      blocks[slot[4 * j + i]] += warped.transpose();
    }
    force_offset_.segment<3>(3 * t[i]).noalias() -= r * rest_forces_[e][i];
  }
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
    const TetrahedronRest& rest = rest_[e];
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        const Eigen::Matrix3d k_ij = stiffnessBlock(lambda_ * rest.volume, mu_ * rest.volume,
                                                    rest.gradients[i], rest.gradients[j]);
        energy += 0.5 * u.segment<3>(3 * i).dot(k_ij * u.segment<3>(3 * j));
      }
    }
  }
  return energy;
}

}  // namespace deformable_sim::core
