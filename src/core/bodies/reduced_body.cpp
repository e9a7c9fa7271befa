#include "deformable_sim/core/bodies/reduced_body.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <utility>

#include "deformable_sim/core/base/rotation.h"
#include "deformable_sim/core/base/wall_clock.h"
#include "deformable_sim/core/bodies/whole_body_participant.h"

namespace deformable_sim::core {

namespace {

using Clock = WallClock;

/// The reduced model of the body's validated mesh; errors name the body.
ReducedDynamics reducedModel(const std::string& where, BodyModel model, const Mesh& mesh,
                             const LinearElasticMaterial& material, const BodyEffects& effects) {
  if (effects.plasticity) {
    throw std::invalid_argument(where + "plasticity needs a finite-element body (" +
                                modelName(model) + " bodies deform homogeneously or not at all)");
  }
  try {
    return ReducedDynamics(model, massProperties(mesh, material.density), material,
                           effects.warping);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(where + e.what());
  }
}

}  // namespace

ReducedBody::ReducedBody(std::string name, Mesh mesh, const LinearElasticMaterial& material,
                         const BodyEffects& effects, const SolverSettings& solver, BodyModel model)
    : Body(std::move(name), std::move(mesh), BodySettings{model, material, effects, solver}),
      reduced_(reducedModel(where(), model, mesh_, material, effects)) {}

std::unique_ptr<ContactParticipant> ReducedBody::contactParticipant() {
  if (reduced_.model() == BodyModel::kRigid) return std::make_unique<RigidParticipant>(*this);
  return std::make_unique<PseudoRigidParticipant>(*this);
}

void ReducedBody::changeMaterial(const LinearElasticMaterial& material) {
  reduced_.setMaterial(massProperties(mesh_, material.density), material);
  nodes_stale_ = true;
}

void ReducedBody::moveBy(const Eigen::Vector3d& centre, const Eigen::Matrix3d& gradient,
                         const Eigen::Vector3d& velocity, const Eigen::Matrix3d& gradient_rate) {
  reduced_.setState(reduced_.centre() + centre, reduced_.gradient() + gradient,
                    reduced_.linearVelocity() + velocity, reduced_.gradientRate() + gradient_rate);
  nodes_stale_ = true;
}

void ReducedBody::assignState(const Eigen::VectorXd& positions, const Eigen::VectorXd& velocities) {
  // The model's motion nearest to the given one: x_i = c + A a_i fitted by least squares
  // (weighted by the nodal masses, so c is the centre of mass), and likewise the velocities.
  const Eigen::Vector3d rest_centre = reduced_.massProperties().centre;
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero(), spread = Eigen::Matrix3d::Zero(),
                  rate = Eigen::Matrix3d::Zero();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero(), velocity = Eigen::Vector3d::Zero();
  double total = 0.0;
  for (int i = 0; i < numNodes(); ++i) {
    total += mass_[i];
    centre += mass_[i] * positions.segment<3>(3 * i);
    velocity += mass_[i] * velocities.segment<3>(3 * i);
  }
  centre /= total;
  velocity /= total;
  for (int i = 0; i < numNodes(); ++i) {
    const Eigen::Vector3d arm = x0_.segment<3>(3 * i) - rest_centre;
    second += mass_[i] * arm * arm.transpose();
    spread += mass_[i] * (positions.segment<3>(3 * i) - centre) * arm.transpose();
    rate += mass_[i] * (velocities.segment<3>(3 * i) - velocity) * arm.transpose();
  }
  if (reduced_.model() == BodyModel::kRigid) {
    // The rotation nearest to the nodes (the rotation factor of the spread, Procrustes), and
    // the angular velocity that fits their velocities best: sum m r x (v - omega x r) = 0.
    Eigen::Vector3d momentum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
    for (int i = 0; i < numNodes(); ++i) {
      const Eigen::Vector3d r = positions.segment<3>(3 * i) - centre;
      momentum += mass_[i] * r.cross(velocities.segment<3>(3 * i) - velocity);
      inertia += mass_[i] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
    }
    const Eigen::Matrix3d rotation = extractRotation(spread);
    const Eigen::Vector3d omega = inertia.ldlt().solve(momentum);
    Eigen::Matrix3d spin;
    spin << 0.0, -omega.z(), omega.y(), omega.z(), 0.0, -omega.x(), -omega.y(), omega.x(), 0.0;
    reduced_.setState(centre, rotation, velocity, spin * rotation);
  } else {
    const Eigen::Matrix3d inverse = second.inverse();
    reduced_.setState(centre, spread * inverse, velocity, rate * inverse);
  }
  nodes_stale_ = true;
}

void ReducedBody::undoStep() {
  reaction_.setZero();  // of the undone step
  reduced_.returnToRemembered();
  nodes_stale_ = true;
}

void ReducedBody::holdChanged(int node, bool held) {
  const auto at = std::lower_bound(constrained_nodes_.begin(), constrained_nodes_.end(), node);
  if (held) {
    constrained_nodes_.insert(at, node);
  } else {
    constrained_nodes_.erase(at);
  }
}

void ReducedBody::updateNodes() const {
  const Eigen::Vector3d rest_centre = reduced_.massProperties().centre;
  const Eigen::Matrix3d& gradient = reduced_.gradient();
  const Eigen::Matrix3d rate = reduced_.gradientRate();
  for (int i = 0; i < numNodes(); ++i) {
    const Eigen::Vector3d arm = x0_.segment<3>(3 * i) - rest_centre;
    x_.segment<3>(3 * i) = reduced_.centre() + gradient * arm;
    v_.segment<3>(3 * i) = reduced_.linearVelocity() + rate * arm;
  }
  nodes_stale_ = false;
  ++node_updates_;
}

StepReport ReducedBody::step(double dt) {
  StepReport report;
  const auto start = Clock::now();
  reduced_.remember();  // its few coordinates, for undoStep()
  sumLoads();
  const RayleighDamping damping = settings_.effects.damping.value_or(RayleighDamping{});
  if (settings_.effects.damping) ++counters_.damping;
  if (settings_.effects.gravity) ++counters_.gravity;
  if (settings_.effects.warping && reduced_.model() == BodyModel::kPseudoRigid) ++counters_.warping;
  if (settings_.effects.reactions) ++counters_.reactions;
  reduced_.step(dt, load_resultant_, settings_.effects.gravity, damping.mass, damping.stiffness,
                nodeConstraints(), settings_.effects.reactions ? &reaction_ : nullptr);
  nodes_stale_ = true;
  report.solves = 1;
  report.times.total = report.times.solve = secondsSince(start);
  return report;
}

StaticReport ReducedBody::solveStaticChecked(const StaticSettings& settings) {
  sumLoads();
  StaticReport report;
  const int iterations =
      reduced_.solveStatic(load_resultant_, settings_.effects.gravity, nodeConstraints(),
                           settings.max_iterations, settings.tolerance, reaction_);
  report.iterations = std::abs(iterations);
  report.converged = iterations > 0;
  nodes_stale_ = true;
  return report;
}

void ReducedBody::sumLoads() {
  if (!loads_stale_) return;
  // Summed when they change, not every step: the step's cost does not depend on the mesh.
  const Eigen::Vector3d rest_centre = reduced_.massProperties().centre;
  load_resultant_ = LoadResultant{};
  for (int i = 0; i < numNodes(); ++i) {
    const Eigen::Vector3d f = external_forces_.segment<3>(3 * i);
    load_resultant_.force += f;
    load_resultant_.first_moment += f * (x0_.segment<3>(3 * i) - rest_centre).transpose();
  }
  loads_stale_ = false;
  ++load_sums_;
}

}  // namespace deformable_sim::core
