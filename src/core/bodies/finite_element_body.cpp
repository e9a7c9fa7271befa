#include "deformable_sim/core/bodies/finite_element_body.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "deformable_sim/core/base/wall_clock.h"
#include "deformable_sim/core/bodies/elastic_participant.h"
#include "deformable_sim/core/materials/neo_hookean_elasticity.h"

namespace deformable_sim::core {

namespace {

using Clock = WallClock;

/// A plane spring's stiffness in units of its node's diagonal in the step matrix: stiff enough to
/// keep the node within a thousandth of its way off the plane, soft enough for block-Jacobi.
constexpr double kPlaneStiffness = 1e3;

std::unique_ptr<ElasticModel> elasticModelFor(const Mesh& mesh,
                                              const LinearElasticMaterial& material) {
  if (material.law == ElasticLaw::kNeoHookean) {
    return std::make_unique<NeoHookeanElasticity>(mesh, material);
  }
  return std::make_unique<CorotationalElasticity>(mesh, material);
}

}  // namespace

FiniteElementBody::FiniteElementBody(std::string name, Mesh mesh,
                                     const LinearElasticMaterial& material,
                                     const BodyEffects& effects, const SolverSettings& solver)
    : Body(std::move(name), std::move(mesh),
           BodySettings{BodyModel::kFiniteElement, material, effects, solver}),
      elasticity_(elasticModelFor(mesh_, material)),
      step_start_(x0_),
      step_forces_(Eigen::VectorXd::Zero(x0_.size())) {
  plane_holds_.reserve(mesh_.numNodes());
  rhs_.resize(x0_.size());
  next_.resize(x0_.size());
  scratch_.resize(x0_.size());
  newton_iterate_ = Eigen::VectorXd::Zero(x0_.size());
  damping_product_ = Eigen::VectorXd::Zero(x0_.size());
  for (Eigen::VectorXd& v : v_history_) v = Eigen::VectorXd::Zero(x0_.size());
  if (solver.method == SolverSettings::Method::kDirect) direct_ = std::make_unique<DirectSolver>();
  elasticity_->setThreads(solver.threads);
  corotational_ = dynamic_cast<const CorotationalElasticity*>(elasticity_.get());
  if (effects.plasticity && !corotational_) {
    throw std::invalid_argument(where() +
                                "plasticity works with the warped stiffness only, not Neo-Hookean");
  }
  if (effects.plasticity) {
    try {
      plasticity_.emplace(mesh_, *effects.plasticity);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(where() + e.what());
    }
    plastic_forces_ = Eigen::VectorXd::Zero(x0_.size());
  }
}

std::unique_ptr<ContactParticipant> FiniteElementBody::contactParticipant() {
  return std::make_unique<ElasticParticipant>(*this);
}

void FiniteElementBody::changeMaterial(const LinearElasticMaterial& material) {
  elasticity_->setMaterial(material);
  stiffness_current_ = false;
  matrixChanged();
  ++matrix_version_;
  cg_.clearPreviousSolutions();
}

void FiniteElementBody::assignState(const Eigen::VectorXd& positions,
                                    const Eigen::VectorXd& velocities) {
  x_ = positions;
  v_ = velocities;
  response_factored_ = false;
  ++matrix_version_;
  restartWarmStart();
  rotations_current_ = false;
}

bool FiniteElementBody::stateIsFinite() const { return x_.allFinite() && v_.allFinite(); }

void FiniteElementBody::undoStep() {
  response_factored_ = false;
  ++matrix_version_;
  reaction_.setZero();  // of the undone step
  x_ = step_start_;
  v_.setZero();
  restartWarmStart();
  rotations_current_ = false;
}

void FiniteElementBody::holdNodeAt(int node, const Eigen::Vector3d& target) {
  if (!constrained_[node]) matrixChanged();
  constrained_[node] = 1;
  targets_.segment<3>(3 * node) = target;
}

void FiniteElementBody::releaseNode(int node) {
  if (constrained_[node]) matrixChanged();
  constrained_[node] = 0;
  reaction_.segment<3>(3 * node).setZero();
}

void FiniteElementBody::holdNodeOnPlane(int node, const Eigen::Vector3d& normal,
                                        const Eigen::Vector3d& target) {
  PlaneHold hold;
  hold.node = node;
  hold.normal = normal;
  hold.offset = normal.dot(target);
  plane_holds_.push_back(hold);
  matrixChanged();
}

void FiniteElementBody::addStepForce(int node, const Eigen::Vector3d& force) {
  step_forces_.segment<3>(3 * node) += force;
  has_step_forces_ = true;
}

void FiniteElementBody::releasePlaneHolds() {
  if (!plane_holds_.empty()) matrixChanged();
  for (const PlaneHold& hold : plane_holds_) reaction_.segment<3>(3 * hold.node).setZero();
  plane_holds_.clear();
  if (has_step_forces_) step_forces_.setZero();
  has_step_forces_ = false;
}

void FiniteElementBody::preparePlaneHolds(double dt) {
  if (plane_holds_.empty()) return;
  const RayleighDamping damping = settings_.effects.damping.value_or(RayleighDamping{});
  const double c_m = 1.0 + dt * damping.mass, c_k = dt * damping.stiffness + dt * dt;
  const BlockSparseMatrix& k = elasticity_->stiffness();
  for (PlaneHold& hold : plane_holds_) {
    const int i = hold.node;
    const double diagonal = c_m * mass_[i] + c_k * k.blocks()[k.diagonalIndex(i)].trace() / 3.0;
    hold.stiffness = kPlaneStiffness * diagonal;
    hold.velocity = (hold.offset - hold.normal.dot(x_.segment<3>(3 * i))) / dt;
  }
}

SystemMatrix FiniteElementBody::stepMatrix(double h) const {
  const RayleighDamping damping = settings_.effects.damping.value_or(RayleighDamping{});
  SystemMatrix a = systemMatrix(1.0 + h * damping.mass, h * damping.stiffness + h * h);
  if (!plane_holds_.empty()) a.planes = &plane_holds_;
  return a;
}

SolveReport FiniteElementBody::solveLastStep(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const SystemMatrix a = stepMatrix(history_dt_);
  x.setZero();
  if (direct_) return solve(a, b, x, false, 0.0);  // the step's own factorization
  SolveReport report;
  if (!response_direct_) response_direct_ = std::make_unique<DirectSolver>();
  if (!response_factored_) {
    if (!response_direct_->factorize(a, constrained_)) return solve(a, b, x, false, 0.0);
    response_factored_ = true;
  }
  response_direct_->applyInverse(b, x);
  report.converged = true;
  return report;
}

void FiniteElementBody::addConstraintForces(const Eigen::VectorXd& dv) {
  if (!settings_.effects.reactions) return;
  const double h = history_dt_;
  for (const PlaneHold& p : plane_holds_) {  // its spring gives way as the node moves along n
    reaction_.segment<3>(3 * p.node) -=
        p.stiffness * p.normal.dot(dv.segment<3>(3 * p.node)) / h * p.normal;
  }
  if (numConstrained(*this) == 0) return;
  stepMatrix(h).multiply(dv, scratch_);
  for (int i = 0; i < numNodes(); ++i) {
    if (constrained_[i]) reaction_.segment<3>(3 * i) += scratch_.segment<3>(3 * i) / h;
  }
}

int FiniteElementBody::updateStiffness(StepTimes* times) {
  const auto start = Clock::now();
  if (followsPositions() && !rotations_current_) {
    const ElasticModel::Update update = elasticity_->linearizeAt(x_);
    inverted_elements_ = update.inverted;
    elastic_energy_ = update.energy;
    rotations_current_ = true;
    stiffness_current_ = false;
  }
  const auto rotated = Clock::now();
  if (!stiffness_current_) {  // without warping: once, and after a change of material
    elasticity_->assemble();
    stiffness_current_ = true;
    matrix_changed_ = true;
  }
  if (times) {
    times->rotations += std::chrono::duration<double>(rotated - start).count();
    times->assembly += secondsSince(rotated);
  }
  return inverted_elements_;
}

SystemMatrix FiniteElementBody::systemMatrix(double mass_coefficient,
                                             double stiffness_coefficient) const {
  SystemMatrix a;
  a.stiffness = &elasticity_->stiffness();
  a.nodal_mass = &mass_;
  a.mass_coefficient = mass_coefficient;
  a.stiffness_coefficient = stiffness_coefficient;
  a.positions = &x_;
  a.threads = settings_.solver.threads;
  return a;
}

SolveReport FiniteElementBody::solve(const SystemMatrix& a, const Eigen::VectorXd& b,
                                     Eigen::VectorXd& x, bool step_start, double reference_floor,
                                     double forcing) {
  if (a.mass_coefficient != last_mass_coefficient_ ||
      a.stiffness_coefficient != last_stiffness_coefficient_) {
    matrix_changed_ = true;
    last_mass_coefficient_ = a.mass_coefficient;
    last_stiffness_coefficient_ = a.stiffness_coefficient;
  }
  SolveReport report;
  if (settings_.solver.method == SolverSettings::Method::kDirect) {
    report = direct_->solve(a, constrained_, b, matrix_changed_, x);
  } else {
    report =
        cg_.solve(a, constrained_, b, settings_.solver, x, step_start, reference_floor, forcing);
  }
  matrix_changed_ = false;
  return report;
}

void FiniteElementBody::restartWarmStart() {
  history_size_ = 0;
  cg_.clearPreviousSolutions();
}

void FiniteElementBody::predictVelocity(Eigen::VectorXd& guess) const {
  // The projected warm start replaces this guess once the solver has solutions to combine.
  const int order =
      settings_.solver.warm_start == SolverSettings::WarmStart::kLastVelocity ? 0 : history_size_;
  // Polynomial extrapolation through the last velocities (backward differences of order 0-3).
  switch (order) {
    case 0:
      guess = v_;
      break;
    case 1:
      guess = 2.0 * v_ - v_history_[0];
      break;
    case 2:
      guess = 3.0 * v_ - 3.0 * v_history_[0] + v_history_[1];
      break;
    default:
      guess = 4.0 * v_ - 6.0 * v_history_[0] + 4.0 * v_history_[1] - v_history_[2];
      break;
  }
}

Eigen::Vector3d FiniteElementBody::stepLoad(int i) const {
  Eigen::Vector3d load = external_forces_.segment<3>(3 * i);
  if (settings_.effects.gravity) load += mass_[i] * *settings_.effects.gravity;
  if (plasticity_) load += plastic_forces_.segment<3>(3 * i);
  if (has_step_forces_) load += step_forces_.segment<3>(3 * i);
  return load;
}

double FiniteElementBody::stepPotential(const Eigen::VectorXd& v, double h, double elastic_energy) {
  const double mass_damping = settings_.effects.damping ? settings_.effects.damping->mass : 0.0;
  double potential = elastic_energy;
  for (int i = 0; i < numNodes(); ++i) {
    const Eigen::Vector3d vi = v.segment<3>(3 * i);
    potential +=
        0.5 * mass_[i] *
            ((vi - v_.segment<3>(3 * i)).squaredNorm() + h * mass_damping * vi.squaredNorm()) -
        h * stepLoad(i).dot(vi);
  }
  for (const PlaneHold& hold : plane_holds_) {
    const double off = hold.normal.dot(v.segment<3>(3 * hold.node)) - hold.velocity;
    potential += 0.5 * hold.stiffness * off * off;
  }
  // Rayleigh's stiffness part, with the linearization's K: left out, the potential's minimum is
  // not the step's answer, and a search from near that answer would halve its way back.
  const double stiffness_damping =
      settings_.effects.damping ? settings_.effects.damping->stiffness : 0.0;
  if (stiffness_damping > 0.0) {
    elasticity_->stiffness().multiply(v, damping_product_);
    potential += 0.5 * h * stiffness_damping * v.dot(damping_product_);
  }
  return potential;
}

void FiniteElementBody::linearizeAtPrediction(double h, RotationSettling& settling,
                                              StepReport& report) {
  // The prediction, or x itself (held nodes at their velocities), whichever lowers the step's
  // potential more: a straight-line prediction of a fast spin stretches the body.
  const ElasticModel::Update predicted = rotateToEnd(h, report);  // at x + h next_
  const double at_prediction = stepPotential(next_, h, predicted.energy);
  newton_iterate_.setZero();
  bool held_move = false;
  for (int i = 0; i < numNodes(); ++i) {
    if (!constrained_[i]) continue;
    newton_iterate_.segment<3>(3 * i) = next_.segment<3>(3 * i);
    held_move = held_move || !next_.segment<3>(3 * i).isZero(0.0);
  }
  if (held_move) end_positions_.noalias() = x_ + h * newton_iterate_;  // in place: no allocation
  const double start_energy =
      held_move ? elasticity_->lawEnergy(end_positions_) : settling.start_energy;
  const double at_start = stepPotential(newton_iterate_, h, start_energy);
  if (at_start < at_prediction) {
    next_ = newton_iterate_;
    rotateToEnd(h, report);
  }
  const auto assembly_start = Clock::now();
  elasticity_->assembleOffset();  // the matrix stays the one of x
  report.times.assembly += secondsSince(assembly_start);
  newton_iterate_ = next_;
  settling.potential = std::min(at_start, at_prediction);
}

ElasticModel::Update FiniteElementBody::searchLine(double h, RotationSettling& settling,
                                                   const ElasticModel::Update& end,
                                                   StepReport& report) {
  constexpr int kMaxHalvings = 12;
  ElasticModel::Update at = end;
  double potential = stepPotential(next_, h, at.energy);
  // Within the law's rounding of its energy, a rise is no rise (a body at rest has only that).
  for (int halving = 0;
       halving < kMaxHalvings && !(potential <= settling.potential + at.energy_rounding);
       ++halving) {
    next_ = 0.5 * (next_ + newton_iterate_);
    at = rotateToEnd(h, report);
    potential = stepPotential(next_, h, at.energy);
  }
  newton_iterate_ = next_;
  settling.potential = potential;
  return at;
}

double FiniteElementBody::setStepRightHandSide(double h) {
  // b = M v - h (K' x + f0' - f_ext - M g); K' x on the solver's threads.
  systemMatrix(0.0, 1.0).multiply(x_, scratch_);
  const Eigen::VectorXd& f0 = elasticity_->forceOffset();
  double free_load2 = 0.0;
  for (int i = 0; i < numNodes(); ++i) {
    const Eigen::Vector3d load = stepLoad(i);
    if (!constrained_[i]) free_load2 += load.squaredNorm();
    rhs_.segment<3>(3 * i) = mass_[i] * v_.segment<3>(3 * i) -
                             h * (scratch_.segment<3>(3 * i) + f0.segment<3>(3 * i) - load);
  }
  // A plane's spring pulls its node to the velocity that puts it on the plane.
  for (const PlaneHold& hold : plane_holds_) {
    rhs_.segment<3>(3 * hold.node) += hold.stiffness * hold.velocity * hold.normal;
  }
  return h * std::sqrt(free_load2);
}

StepReport FiniteElementBody::step(double dt) {
  StepReport report;
  const auto start = Clock::now();
  step_start_ = x_;
  response_factored_ = false;           // the step's matrix is new
  elasticity_->useExactTangent(false);  // a step starts with the cheaper matrix, where there is one
  report.inverted_elements = updateStiffness(&report.times);
  if (plasticity_) {
    plasticity_->step(mesh_, *corotational_, x_, dt, plastic_forces_);
    ++counters_.plasticity;
  }
  if (settings_.effects.damping) ++counters_.damping;
  if (settings_.effects.gravity) ++counters_.gravity;
  if (settings_.effects.warping) ++counters_.warping;
  if (settings_.effects.reactions) ++counters_.reactions;
  // Constrained nodes reach their targets at the end of the step (at an even pace if it is split).
  prescribed_velocity_.resize(x_.size());
  for (int i = 0; i < numNodes(); ++i) {
    prescribed_velocity_.segment<3>(3 * i) =
        constrained_[i] ? Eigen::Vector3d((targets_.segment<3>(3 * i) - x_.segment<3>(3 * i)) / dt)
                        : Eigen::Vector3d::Zero();
  }
  preparePlaneHolds(dt);
  advance(dt, 0, report);
  report.times.total = secondsSince(start);
  return report;
}

void FiniteElementBody::advance(double h, int depth, StepReport& report) {
  updateStiffness(&report.times);  // nothing to do unless a split step begins here
  const SystemMatrix a = stepMatrix(h);
  if (h != history_dt_) history_size_ = 0;  // the history is of another step size
  predictVelocity(next_);
  for (int i = 0; i < numNodes(); ++i) {
    if (constrained_[i]) next_.segment<3>(3 * i) = prescribed_velocity_.segment<3>(3 * i);
  }
  // Solved with the rotations at the start. With warping, the rotations at the end (which the
  // next step starts from) are then compared with them: the solve was backward Euler for the
  // energy with the solve's rotations, which loses energy; when the change of rotations gains
  // more than that, the step is solved again with the newer rotations, warm-started from the
  // last solution (a fixed point of backward Euler with the exact corotational force). Where
  // that does not settle (elements turning by radians within the step), the step is split in
  // two halves, each solved the same way.
  RotationSettling settling;
  settling.start_energy = elastic_energy_;
  settling.solve_start_energy = settling.start_energy;
  // A law that follows the positions starts Newton's iterations at the predicted velocity: the
  // first solve is then only the prediction's error off the law, not the whole step's motion.
  if (!corotational_ && followsPositions()) linearizeAtPrediction(h, settling, report);
  int matrix_since = 0;  // solves before the current matrix
  // Matrices of a law that follows the positions assembled within the step (the corotational
  // law's escalation is the split alone).
  int refreshes = corotational_ || elasticity_->usesExactTangent() ? 2 : 0;
  for (int solves = 1;; ++solves) {
    solveVelocity(a, h, solves == 1, report);
    if (!followsPositions()) break;
    ElasticModel::Update end = rotateToEnd(h, report);
    if (!corotational_) end = searchLine(h, settling, end, report);
    if (settings_.solver.max_rotation_updates == 0) break;
    const EnergyCheck check =
        corotational_ ? checkRotationEnergy(a, end, settling) : checkNewtonResidual(a, end, h);
    if (!corotational_) settling.product_is_current = true;  // the check's A v+
    if (!check.gains) break;
    // Converging, the excess shrinks several times over from one solve to the next; where it
    // does not, more solves will not settle it either.
    const bool stalled = check.excess > 0.5 * settling.last_excess;
    settling.last_excess = check.excess;
    if (report.solves >= kMaxSolves) break;  // keep the last solution: a step's time is bounded
    const bool slow = stalled || solves - matrix_since > settings_.solver.max_rotation_updates;
    bool new_matrix = corotational_;
    if (slow && refreshes < 2) {
      // The iterations crawl with the step's matrix: the warped stiffness rotated to this
      // iterate (the body turned within the step), then the law's own tangent.
      if (refreshes++ == 1) elasticity_->useExactTangent(true);
      new_matrix = true;
      settling.last_excess = std::numeric_limits<double>::infinity();
      matrix_since = solves;
    } else if (slow) {
      if (depth >= kMaxSplits) break;
      // Start again from x in two halves; the rotations now are those of a discarded end.
      rotations_current_ = false;
      elastic_energy_ = settling.start_energy;
      ++report.splits;
      advance(0.5 * h, depth + 1, report);
      advance(0.5 * h, depth + 1, report);
      return;
    }
    assembleForNextSolve(new_matrix, settling, report);
  }
  finishAdvance(a, h, settling.product_is_current);
}

void FiniteElementBody::assembleForNextSolve(bool new_matrix, RotationSettling& settling,
                                             StepReport& report) {
  const auto assembly_start = Clock::now();
  // A law that follows the positions keeps one matrix from one iteration to the next (its
  // Rayleigh damping, which takes K, then damps alike in all): only its offset follows.
  if (new_matrix) {
    elasticity_->assemble();
    matrix_changed_ = true;
  } else {
    elasticity_->assembleOffset();
  }
  settling.product_is_current = false;
  if (corotational_) settling.solve_start_energy = elasticity_->elasticEnergy(x_);
  report.times.assembly += secondsSince(assembly_start);
}

void FiniteElementBody::solveVelocity(const SystemMatrix& a, double h, bool step_start,
                                      StepReport& report) {
  // Where the loads balance the elastic forces (a body at rest), b is what rounding leaves of
  // them: CG's residual is measured against the loads' impulse there instead.
  load_impulse_ = setStepRightHandSide(h);
  const auto solve_start = Clock::now();
  // A Newton iteration after the first starts from the last, already close: CG need only take a
  // fraction of the law's residual out there (inexact Newton), the next iteration sees the rest.
  constexpr double kNewtonForcing = 0.05;
  const double forcing = corotational_ ? 0.0 : kNewtonForcing;
  const SolveReport solved = solve(a, rhs_, next_, step_start, load_impulse_, forcing);
  report.times.solve += secondsSince(solve_start);
  report.times.preconditioner += solved.preconditioner_seconds;
  report.solve.iterations += solved.iterations;
  report.solve.relative_residual = solved.relative_residual;
  report.solve.converged = solved.converged;
  ++report.solves;
}

ElasticModel::Update FiniteElementBody::rotateToEnd(double h, StepReport& report) {
  end_positions_ = x_ + h * next_;
  const auto rotations_start = Clock::now();
  const ElasticModel::Update end = elasticity_->linearizeAt(end_positions_);
  report.times.rotations += secondsSince(rotations_start);
  end_inverted_elements_ = end.inverted;
  elastic_energy_ = end.energy;
  report.largest_rotation_change = end.largest_change;
  return end;
}

FiniteElementBody::EnergyCheck FiniteElementBody::checkRotationEnergy(
    const SystemMatrix& a, const ElasticModel::Update& end, RotationSettling& settling) {
  // What the step dissipates, 1/2 dv^T M dv + 1/2 h^2 v+^T K' v+ (+ damping's h v+^T C v+, left
  // out), against what the change of rotations adds at its start and end. The stiffness part
  // costs a product with A: only when the mass part does not cover the gain already.
  double velocity_change2 = 0.0, kinetic2 = 0.0, start_kinetic2 = 0.0;  // sums of m |v|^2
  for (int i = 0; i < numNodes(); ++i) {
    velocity_change2 += mass_[i] * (next_.segment<3>(3 * i) - v_.segment<3>(3 * i)).squaredNorm();
    kinetic2 += mass_[i] * next_.segment<3>(3 * i).squaredNorm();
    start_kinetic2 += mass_[i] * v_.segment<3>(3 * i).squaredNorm();
  }
  const double gained =
      (end.energy - end.energy_before) + (settling.solve_start_energy - settling.start_energy);
  // A gain below kEnergyResolution of the body's energy is below what the step resolves (CG
  // stops at a relative residual of 1e-6 by default): a ball at rest on a floor gained 5e-9 of
  // its energy a step from rotations turning by 5e-6 rad, beyond the 1e-12 once allowed, and
  // solved its step again and split it to the limit, 254 solves a step.
  constexpr double kEnergyResolution = 1e-8;
  const double roundoff = kEnergyResolution * (settling.start_energy + end.energy +
                                               0.5 * start_kinetic2 + 0.5 * kinetic2);
  double dissipated = 0.5 * velocity_change2;
  if (gained > dissipated + roundoff) {
    a.multiply(next_, scratch_);
    settling.product_is_current = true;
    dissipated += 0.5 * (next_.dot(scratch_) - a.mass_coefficient * kinetic2);
  }
  return {gained > dissipated + roundoff, gained - dissipated};
}

FiniteElementBody::EnergyCheck FiniteElementBody::checkNewtonResidual(
    const SystemMatrix& a, const ElasticModel::Update& end, double h) {
  // On the free rows, implicit Euler's residual with the law's force is A v - b (what CG left,
  // and the line search, with the linearization's force) less h (f - f_linearized) at the end.
  // Done when the law's part is on every free node below kNewtonTolerance of the step's change
  // of momentum and elastic impulse (not of its momentum: a spinning body's would hide errors of
  // its spin), and CG's part is within CG's own tolerance or that bound (a solve cut short, as a
  // later iteration's are, leaves more).
  constexpr double kNewtonTolerance = 1e-6;
  a.multiply(next_, scratch_);
  const Eigen::VectorXd& mismatch = elasticity_->forceMismatch();
  double law = 0.0, solve = 0.0, solve2 = 0.0, reference2 = 0.0, momentum = 0.0;
  for (int i = 0; i < numNodes(); ++i) {
    if (constrained_[i]) continue;
    const Eigen::Vector3d left = scratch_.segment<3>(3 * i) - rhs_.segment<3>(3 * i);
    law = std::max(law, h * mismatch.segment<3>(3 * i).lpNorm<Eigen::Infinity>());
    solve = std::max(solve, left.lpNorm<Eigen::Infinity>());
    solve2 += left.squaredNorm();
    reference2 += rhs_.segment<3>(3 * i).squaredNorm();
    momentum = std::max(
        momentum,
        mass_[i] * (next_.segment<3>(3 * i) - v_.segment<3>(3 * i)).lpNorm<Eigen::Infinity>());
  }
  const double bound =
      kNewtonTolerance * (momentum + h * end.largest_force) + h * end.force_rounding;
  const double cg_bound =
      settings_.solver.tolerance * std::max(std::sqrt(reference2), load_impulse_);
  const bool done = law <= bound && (solve <= bound || std::sqrt(solve2) <= cg_bound);
  return {!done, std::max(law, solve)};
}

void FiniteElementBody::finishAdvance(const SystemMatrix& a, double h, bool product_is_current) {
  // A v+ - b = h (M (v+ - v) / h - f_ext - f_elastic - f_damping): h times the constraint force.
  if (settings_.effects.reactions) {
    if (!product_is_current) a.multiply(next_, scratch_);
    for (int i = 0; i < numNodes(); ++i) {
      reaction_.segment<3>(3 * i) =
          constrained_[i]
              ? Eigen::Vector3d((scratch_.segment<3>(3 * i) - rhs_.segment<3>(3 * i)) / h)
              : Eigen::Vector3d::Zero();
    }
    for (const PlaneHold& p : plane_holds_) {  // what the plane's spring exerts on its node
      const double lag = p.velocity - p.normal.dot(next_.segment<3>(3 * p.node));
      reaction_.segment<3>(3 * p.node) = p.stiffness * lag / h * p.normal;
    }
  }
  if (followsPositions()) {
    // x+ is end_positions_ (bit for bit: the same sum); its rotations are already computed.
    std::swap(x_, end_positions_);
    rotations_current_ = true;
    stiffness_current_ = false;
    inverted_elements_ = end_inverted_elements_;
  } else {
    x_ += h * next_;
  }
  // History for the next prediction: shift by swapping, so nothing is copied or allocated.
  std::swap(v_history_[2], v_history_[1]);
  std::swap(v_history_[1], v_history_[0]);
  std::swap(v_history_[0], v_);  // v_history_[0] = last velocity; v_ holds a dead buffer
  v_ = next_;
  history_size_ = std::min(history_size_ + 1, 3);
  if (h != history_dt_) ++matrix_version_;
  history_dt_ = h;
}

StaticReport FiniteElementBody::solveStaticChecked(const StaticSettings& settings) {
  StaticReport report;
  if (settings_.effects.warping) ++counters_.warping;
  // Newton's own tangent, where the law has a choice: quadratic convergence to equilibrium.
  if (!elasticity_->usesExactTangent()) {
    elasticity_->useExactTangent(true);
    stiffness_current_ = false;
  }
  const SystemMatrix a = systemMatrix(0.0, 1.0);
  Eigen::VectorXd load = external_forces_;
  if (settings_.effects.gravity) {
    for (int i = 0; i < numNodes(); ++i)
      load.segment<3>(3 * i) += mass_[i] * *settings_.effects.gravity;
  }
  const Eigen::VectorXd start = x_;
  for (int s = 1; s <= settings.load_steps; ++s) {
    const double fraction = static_cast<double>(s) / settings.load_steps;
    // The corotational fixed point can oscillate at large rotations on fine meshes: relax the
    // update while its size grows, and return to full steps while it shrinks.
    double relaxation = 1.0, previous_change = std::numeric_limits<double>::infinity();
    for (int iteration = 0; iteration < settings.max_iterations; ++iteration) {
      const double change = staticIteration(a, load, start, fraction, report);
      relaxation = change > previous_change ? std::max(0.125, 0.5 * relaxation)
                                            : std::min(1.0, 1.25 * relaxation);
      previous_change = change;
      relaxTowardsNext(relaxation);
      if (!followsPositions() || report.last_change <= settings.tolerance) break;
    }
    report.converged = report.last_solve.converged &&
                       (!followsPositions() || report.last_change <= settings.tolerance);
  }
  v_.setZero();
  restartWarmStart();
  setStaticReactions(load);
  return report;
}

double FiniteElementBody::staticIteration(const SystemMatrix& a, const Eigen::VectorXd& load,
                                          const Eigen::VectorXd& start, double fraction,
                                          StaticReport& report) {
  updateStiffness();
  // Solve K' dx = f - f0' - K' x for the change dx, so that CG's relative tolerance is
  // measured against the out-of-balance force, not against K' x (for a stiff body far larger
  // than the load: CG then stopped at once with no displacement at all).
  elasticity_->stiffness().multiply(x_, scratch_);
  rhs_ = fraction * load - elasticity_->forceOffset() - scratch_;
  next_.setZero();
  for (int i = 0; i < numNodes(); ++i) {
    if (constrained_[i]) {
      next_.segment<3>(3 * i) = start.segment<3>(3 * i) +
                                fraction * (targets_.segment<3>(3 * i) - start.segment<3>(3 * i)) -
                                x_.segment<3>(3 * i);
    }
  }
  report.last_solve = solve(a, rhs_, next_);
  next_ += x_;
  report.linear_iterations += report.last_solve.iterations;
  ++report.iterations;
  const double change = (next_ - x_).norm();
  const double displacement = (next_ - x0_).norm();
  report.last_change = displacement > 0.0 ? change / displacement : change;
  return change;
}

void FiniteElementBody::relaxTowardsNext(double relaxation) {
  for (int i = 0; i < numNodes(); ++i) {
    x_.segment<3>(3 * i) =
        constrained_[i]
            ? Eigen::Vector3d(next_.segment<3>(3 * i))
            : Eigen::Vector3d(x_.segment<3>(3 * i) +
                              relaxation * (next_.segment<3>(3 * i) - x_.segment<3>(3 * i)));
  }
  rotations_current_ = false;
}

void FiniteElementBody::setStaticReactions(const Eigen::VectorXd& load) {
  // Reactions at equilibrium, with the stiffness of the final configuration.
  updateStiffness();
  elasticity_->stiffness().multiply(x_, scratch_);
  for (int i = 0; i < numNodes(); ++i) {
    reaction_.segment<3>(3 * i) =
        constrained_[i]
            ? Eigen::Vector3d(scratch_.segment<3>(3 * i) +
                              elasticity_->forceOffset().segment<3>(3 * i) - load.segment<3>(3 * i))
            : Eigen::Vector3d::Zero();
  }
}

double FiniteElementBody::kineticEnergy() const {
  double energy = 0.0;
  for (int i = 0; i < numNodes(); ++i)
    energy += 0.5 * mass_[i] * v_.segment<3>(3 * i).squaredNorm();
  return energy;
}

double FiniteElementBody::elasticEnergy() const {
  if (followsPositions() && rotations_current_) return elastic_energy_;  // computed with them
  return elasticity_->elasticEnergy(x_);
}

}  // namespace deformable_sim::core
