#include "deformable_sim/core/materials/neo_hookean_elasticity.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "deformable_sim/core/base/rotation.h"

namespace deformable_sim::core {

namespace {

NeoHookean lawOf(const LinearElasticMaterial& material) {
  validate(material);
  return NeoHookean::fromYoungPoisson(material.youngs_modulus, material.poisson_ratio);
}

}  // namespace

NeoHookeanElasticity::NeoHookeanElasticity(const Mesh& mesh, const LinearElasticMaterial& material)
    : elements_(mesh, lawOf(material)),
      stiffness_(nodeNeighbours(mesh)),
      force_offset_(Eigen::VectorXd::Zero(3 * mesh.numNodes())),
      rotations_(elements_.numElements(), Eigen::Matrix3d::Identity()),
      linearized_at_(3 * mesh.numNodes()),
      product_(3 * mesh.numNodes()),
      forces_(3 * mesh.numNodes()) {
  constexpr int n = HyperelasticElements::kMaxNodes;
  block_index_.resize(elements_.numElements());
  for (int e = 0; e < elements_.numElements(); ++e) {
    const std::array<int, n>& nodes = elements_.elementNodes(e);
    for (int i = 0; i < elements_.elementSize(e); ++i) {
      for (int j = 0; j < elements_.elementSize(e); ++j)
        block_index_[e][n * i + j] = stiffness_.blockIndex(nodes[i], nodes[j]);
    }
  }
  for (int i = 0; i < mesh.numNodes(); ++i) linearized_at_.segment<3>(3 * i) = mesh.positions[i];
}

void NeoHookeanElasticity::setMaterial(const LinearElasticMaterial& material) {
  elements_.setLaw(lawOf(material));
  assembled_ = false;
  const Eigen::VectorXd at = linearized_at_;  // the same positions, under the new law
  linearizeAt(at);
}

ElasticModel::Update NeoHookeanElasticity::linearizeAt(const Eigen::VectorXd& x) {
  Update update;
  update.energy_before = assembled_ ? elasticEnergy(x) : elements_.energy(x);
  double largest_change2 = 0.0;  // |R_new - R_old|^2 (Frobenius) = 8 sin^2(angle / 2)
  for (int e = 0; e < elements_.numElements(); ++e) {
    update.energy += elements_.elementEnergy(e, x, update.inverted);
    const Eigen::Matrix3d r = extractRotation(elements_.elementDeformationGradient(e, x));
    largest_change2 = std::max(largest_change2, (r - rotations_[e]).squaredNorm());
    rotations_[e] = r;
  }
  update.largest_change = 2.0 * std::asin(std::min(1.0, std::sqrt(largest_change2 / 8.0)));
  // The law's force at x against the last linearization's, -(K x + f0).
  forces_.setZero();
  for (int e = 0; e < elements_.numElements(); ++e) {
    const auto f = elements_.elementForces(e, x);
    const std::array<int, HyperelasticElements::kMaxNodes>& nodes = elements_.elementNodes(e);
    for (int i = 0; i < elements_.elementSize(e); ++i)
      forces_.segment<3>(3 * nodes[i]) += f.segment<3>(3 * i);
  }
  update.largest_force = forces_.lpNorm<Eigen::Infinity>();
  if (assembled_) {
    stiffness_.multiply(x, product_);
    update.force_mismatch = (forces_ + product_ + force_offset_).lpNorm<Eigen::Infinity>();
  } else {
    update.force_mismatch = std::numeric_limits<double>::infinity();
  }
  linearized_at_ = x;
  energy_at_ = update.energy;
  assembled_ = false;
  return update;
}

void NeoHookeanElasticity::assemble() {
  // K: each element's projected tangent; f0 = -f(x0) - K x0, so that K x0 + f0 = -f(x0).
  constexpr int n = HyperelasticElements::kMaxNodes;
  stiffness_.setZero();
  force_offset_.setZero();
  std::vector<Eigen::Matrix3d>& blocks = stiffness_.blocks();
  for (int e = 0; e < elements_.numElements(); ++e) {
    const HyperelasticElements::ElementMatrix k = elements_.elementTangent(e, linearized_at_, true);
    const std::array<int, n>& nodes = elements_.elementNodes(e);
    for (int i = 0; i < elements_.elementSize(e); ++i) {
      for (int j = 0; j < elements_.elementSize(e); ++j)
        blocks[block_index_[e][n * i + j]] += k.block<3, 3>(3 * i, 3 * j);
    }
  }
  stiffness_.multiply(linearized_at_, product_);
  force_offset_ = -forces_ - product_;
  energy_constant_ =
      energy_at_ - 0.5 * linearized_at_.dot(product_) - force_offset_.dot(linearized_at_);
  assembled_ = true;
}

double NeoHookeanElasticity::elasticEnergy(const Eigen::VectorXd& x) const {
  if (!assembled_) return elements_.energy(x);
  stiffness_.multiply(x, product_);
  return 0.5 * x.dot(product_) + force_offset_.dot(x) + energy_constant_;
}

}  // namespace deformable_sim::core
