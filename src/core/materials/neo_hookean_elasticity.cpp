#include "deformable_sim/core/materials/neo_hookean_elasticity.h"

#include <cassert>
#include <cmath>
#include <limits>

namespace deformable_sim::core {

namespace {

NeoHookean lawOf(const LinearElasticMaterial& material) {
  validate(material);
  return NeoHookean::fromYoungPoisson(material.youngs_modulus, material.poisson_ratio);
}

}  // namespace

NeoHookeanElasticity::NeoHookeanElasticity(const Mesh& mesh, const LinearElasticMaterial& material)
    : elements_(mesh, lawOf(material)),
      warped_(mesh, material),
      stiffness_(nodeNeighbours(mesh)),
      force_offset_(Eigen::VectorXd::Zero(3 * mesh.numNodes())),
      linearized_at_(3 * mesh.numNodes()),
      product_(3 * mesh.numNodes()),
      forces_(3 * mesh.numNodes()),
      mismatch_(3 * mesh.numNodes()) {
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
  assert(warped_.stiffness().numBlocks() == stiffness_.numBlocks());  // one pattern, one order
}

void NeoHookeanElasticity::setMaterial(const LinearElasticMaterial& material) {
  elements_.setLaw(lawOf(material));
  warped_.setMaterial(material);
  has_matrix_ = false;
  const Eigen::VectorXd at = linearized_at_;  // the same positions, under the new law
  linearizeAt(at);
}

void NeoHookeanElasticity::setThreads(int threads) { warped_.setThreads(threads); }

ElasticModel::Update NeoHookeanElasticity::linearizeAt(const Eigen::VectorXd& x) {
  Update update;  // the elements' rotations wait for a warped assembly
  // The law's energy and forces at x, one pass over the elements.
  forces_.setZero();
  HyperelasticElements::ElementVector f;
  for (int e = 0; e < elements_.numElements(); ++e) {
    update.energy += elements_.elementEnergyAndForces(e, x, update.inverted, f);
    const std::array<int, HyperelasticElements::kMaxNodes>& nodes = elements_.elementNodes(e);
    for (int i = 0; i < elements_.elementSize(e); ++i)
      forces_.segment<3>(3 * nodes[i]) += f.segment<3>(3 * i);
  }
  update.largest_force = forces_.lpNorm<Eigen::Infinity>();
  // W sums C10 J^(-2/3) I1 and -3 C10 (and more) over the elements: their rounding.
  constexpr double kRounding = 64.0 * std::numeric_limits<double>::epsilon();
  update.energy_rounding =
      kRounding * (std::abs(update.energy) + 3.0 * elements_.law().c10() * elements_.volume());
  // The law's force at x against the last linearization's, -(K x + f0).
  if (has_matrix_) {
    update.energy_before = elasticEnergy(x);  // leaves K x in product_
    mismatch_ = forces_ + product_ + force_offset_;
    update.force_rounding = kRounding * product_.lpNorm<Eigen::Infinity>();
  } else {
    update.energy_before = update.energy;
    mismatch_.setConstant(std::numeric_limits<double>::infinity());
  }
  linearized_at_ = x;
  energy_at_ = update.energy;
  product_is_of_x0_ = has_matrix_;
  return update;
}

void NeoHookeanElasticity::assemble() {
  // K, then f0 = -f(x0) - K x0, so that K x0 + f0 = -f(x0).
  if (exact_tangent_) {
    assembleExactTangent();
  } else {
    warped_.linearizeAt(linearized_at_);
    warped_.assemble();
    stiffness_.blocks() = warped_.stiffness().blocks();  // the same pattern: no allocation
  }
  has_matrix_ = true;
  product_is_of_x0_ = false;  // a new K
  setOffset();
}

void NeoHookeanElasticity::assembleOffset() {
  if (!has_matrix_) {
    assemble();  // no K of this material yet to keep
    return;
  }
  setOffset();
}

void NeoHookeanElasticity::setOffset() {
  if (!product_is_of_x0_) stiffness_.multiply(linearized_at_, product_);
  force_offset_ = -forces_ - product_;
  energy_constant_ =
      energy_at_ - 0.5 * linearized_at_.dot(product_) - force_offset_.dot(linearized_at_);
}

void NeoHookeanElasticity::assembleExactTangent() {
  constexpr int n = HyperelasticElements::kMaxNodes;
  stiffness_.setZero();
  std::vector<Eigen::Matrix3d>& blocks = stiffness_.blocks();
  for (int e = 0; e < elements_.numElements(); ++e) {
    const HyperelasticElements::ElementMatrix k = elements_.elementTangent(e, linearized_at_, true);
    for (int i = 0; i < elements_.elementSize(e); ++i) {
      for (int j = 0; j < elements_.elementSize(e); ++j)
        blocks[block_index_[e][n * i + j]] += k.block<3, 3>(3 * i, 3 * j);
    }
  }
}

double NeoHookeanElasticity::elasticEnergy(const Eigen::VectorXd& x) const {
  if (!has_matrix_) return elements_.energy(x);
  stiffness_.multiply(x, product_);
  product_is_of_x0_ = false;  // of x
  return 0.5 * x.dot(product_) + force_offset_.dot(x) + energy_constant_;
}

}  // namespace deformable_sim::core
