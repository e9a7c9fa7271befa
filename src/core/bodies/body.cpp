#include "deformable_sim/core/bodies/body.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "deformable_sim/core/base/rotation.h"
#include "deformable_sim/core/base/wall_clock.h"
#include "deformable_sim/core/elements/cell.h"
#include "deformable_sim/core/elements/parameter_limits.h"

namespace deformable_sim::core {

namespace {

using Clock = WallClock;

/// A plane spring's stiffness in units of its node's diagonal in the step matrix: stiff enough to
/// keep the node within a thousandth of its way off the plane, soft enough for block-Jacobi.
constexpr double kPlaneStiffness = 1e3;

void validateCells(const std::string& where, const Mesh& mesh);

// The readers validate files; this guards meshes built in code. Throws naming the element/node.
void validateMesh(const std::string& body, const Mesh& mesh) {
  const std::string where = "body '" + body + "': ";
  if (mesh.numElements() == 0) throw std::invalid_argument(where + "mesh has no elements");
  if (mesh.node_numbers.size() != mesh.positions.size()) {
    throw std::invalid_argument(where + "mesh has " + std::to_string(mesh.positions.size()) +
                                " positions but " + std::to_string(mesh.node_numbers.size()) +
                                " node numbers");
  }
  for (int i = 0; i < mesh.numNodes(); ++i) {
    if (!mesh.positions[i].allFinite()) {
      throw std::invalid_argument(where + "node " + std::to_string(mesh.node_numbers[i]) +
                                  " has a non-finite coordinate");
    }
  }
  for (int e = 0; e < mesh.numTetrahedra(); ++e) {
    const Tetrahedron& t = mesh.tetrahedra[e];
    for (int i : t) {
      if (i < 0 || i >= mesh.numNodes()) {
        throw std::invalid_argument(where + "tetrahedron " + std::to_string(e) +
                                    " refers to node index " + std::to_string(i) +
                                    " outside the mesh");
      }
    }
    if (!(signedVolume(mesh.positions, t) > 0.0)) {
      throw std::invalid_argument(where + "tetrahedron " + std::to_string(e) +
                                  " has non-positive volume");
    }
  }
  validateCells(where, mesh);
}

// The cells' node indices, shapes and material fractions.
void validateCells(const std::string& where, const Mesh& mesh) {
  if (!mesh.cell_fractions.empty() && mesh.cell_fractions.size() != mesh.cells.size()) {
    throw std::invalid_argument(where + "mesh has " + std::to_string(mesh.cells.size()) +
                                " cells but " + std::to_string(mesh.cell_fractions.size()) +
                                " cell fractions");
  }
  for (size_t c = 0; c < mesh.cells.size(); ++c) {
    const Cell& cell = mesh.cells[c];
    const std::string name = "cell " + std::to_string(c) + ": ";
    for (int k = 0; k < cell.size(); ++k) {
      if (cell.nodes[k] < 0 || cell.nodes[k] >= mesh.numNodes()) {
        throw std::invalid_argument(where + name + "refers to node index " +
                                    std::to_string(cell.nodes[k]) + " outside the mesh");
      }
    }
    if (const OctantFractions* octants = mesh.cellOctants(c)) {
      for (double f : *octants) {
        if (!(f >= 0.0 && f <= 1.0)) {
          throw std::invalid_argument(where + name + "octant fraction " + std::to_string(f) +
                                      " outside [0, 1]");
        }
      }
      if (!(mesh.cellFraction(c) > 0.0)) {
        throw std::invalid_argument(where + name + "holds no material");
      }
    }
    try {
      computeCellRest(cell.type, cellCorners(cell, mesh.positions));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(where + name + e.what());
    }
  }
}

Eigen::VectorXd stack(const std::vector<Eigen::Vector3d>& points) {
  Eigen::VectorXd stacked(3 * points.size());
  for (size_t i = 0; i < points.size(); ++i) stacked.segment<3>(3 * i) = points[i];
  return stacked;
}

const Mesh& validated(const std::string& name, const Mesh& mesh) {
  validateMesh(name, mesh);
  return mesh;
}

}  // namespace

std::vector<std::string> effectNames(const BodyEffects& effects, BodyModel model) {
  std::vector<std::string> names;
  if (effects.warping && model != BodyModel::kRigid) names.emplace_back("warping");
  if (effects.gravity) names.emplace_back("gravity");
  if (effects.damping) names.emplace_back("damping");
  if (effects.plasticity) names.emplace_back("plasticity");
  if (effects.stress_colouring) names.emplace_back("stress_colouring");
  if (effects.reactions) names.emplace_back("reactions");
  return names;
}

Body::Body(std::string name, Mesh mesh, const LinearElasticMaterial& material,
           const BodyEffects& effects, const SolverSettings& solver, BodyModel model)
    : name_(std::move(name)),
      model_(model),
      mesh_(std::move(mesh)),
      material_(material),
      effects_(effects),
      solver_settings_(solver),
      x0_(stack(validated(name_, mesh_).positions)),
      x_(x0_),
      v_(Eigen::VectorXd::Zero(x0_.size())),
      remembered_positions_(x0_),
      mass_(lumpedMasses(mesh_, material.density)),
      constrained_(mesh_.numNodes(), 0),
      targets_(x0_),
      external_forces_(Eigen::VectorXd::Zero(x0_.size())),
      reaction_(Eigen::VectorXd::Zero(x0_.size())),
      step_forces_(Eigen::VectorXd::Zero(x0_.size())) {
  plane_holds_.reserve(mesh_.numNodes());
  try {
    validate(material);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("body '" + name_ + "': " + e.what());
  }
  setSolverLimits(solver.tolerance, solver.max_iterations);
  setDamping(effects.damping);
  if (solver.threads < 1 || solver.coarse_refresh_interval < 1) {
    throw std::invalid_argument("body '" + name_ +
                                "': solver threads and coarse_refresh_interval must be >= 1");
  }
  if (model != BodyModel::kFiniteElement) {
    if (effects.plasticity) {
      throw std::invalid_argument("body '" + name_ + "': plasticity needs a finite-element body (" +
                                  modelName(model) + " bodies deform homogeneously or not at all)");
    }
    try {
      reduced_.emplace(model, massProperties(mesh_, material.density), material, effects.warping);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("body '" + name_ + "': " + e.what());
    }
    return;
  }
  elasticity_.emplace(mesh_, material);
  rhs_.resize(x0_.size());
  next_.resize(x0_.size());
  scratch_.resize(x0_.size());
  for (Eigen::VectorXd& v : v_history_) v = Eigen::VectorXd::Zero(x0_.size());
  if (solver.method == SolverSettings::Method::kDirect) direct_ = std::make_unique<DirectSolver>();
  elasticity_->setThreads(solver.threads);
  if (effects.plasticity) {
    try {
      plasticity_.emplace(mesh_, *effects.plasticity);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("body '" + name_ + "': " + e.what());
    }
    plastic_forces_ = Eigen::VectorXd::Zero(x0_.size());
  }
}

void Body::setMaterial(const LinearElasticMaterial& material) {
  try {
    validate(material);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("body '" + name_ + "': " + e.what());
  }
  if (reduced_) {
    reduced_->setMaterial(massProperties(mesh_, material.density), material);
    nodes_stale_ = true;
  }
  material_ = material;
  if (elasticity_) elasticity_->setMaterial(material);
  mass_ = lumpedMasses(mesh_, material.density);
  stiffness_current_ = false;
  matrix_changed_ = true;
  cg_.clearPreviousSolutions();
}

void Body::setDamping(const std::optional<RayleighDamping>& damping) {
  if (damping) checkDamping(damping->mass, damping->stiffness, "body '" + name_ + "': ");
  effects_.damping = damping;
}

void Body::setSolverLimits(double tolerance, int max_iterations) {
  checkSolverLimits(tolerance, max_iterations, "body '" + name_ + "': ");
  solver_settings_.tolerance = tolerance;
  solver_settings_.max_iterations = max_iterations;
}

void Body::addGroup(const std::string& name, std::vector<int> nodes) {
  for (int i : nodes) {
    if (i < 0 || i >= numNodes()) {
      throw std::invalid_argument("body '" + name_ + "': group '" + name + "' has node index " +
                                  std::to_string(i) + " out of range");
    }
  }
  groups_[name] = std::move(nodes);
}

void Body::moveReducedBy(const Eigen::Vector3d& centre, const Eigen::Matrix3d& gradient,
                         const Eigen::Vector3d& velocity, const Eigen::Matrix3d& gradient_rate) {
  if (!reduced_)
    throw std::logic_error("body '" + name_ + "': it has no rigid or pseudo-rigid model");
  reduced_->setState(reduced_->centre() + centre, reduced_->gradient() + gradient,
                     reduced_->linearVelocity() + velocity,
                     reduced_->gradientRate() + gradient_rate);
  nodes_stale_ = true;
}

void Body::setState(const Eigen::VectorXd& positions, const Eigen::VectorXd& velocities) {
  if (positions.size() != x_.size() || velocities.size() != v_.size()) {
    throw std::invalid_argument("body '" + name_ + "': state of the wrong size");
  }
  if (reduced_) {
    // The model's motion nearest to the given one: x_i = c + A a_i fitted by least squares
    // (weighted by the nodal masses, so c is the centre of mass), and likewise the velocities.
    const Eigen::Vector3d rest_centre = reduced_->massProperties().centre;
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
    if (model_ == BodyModel::kRigid) {
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
      reduced_->setState(centre, rotation, velocity, spin * rotation);
    } else {
      const Eigen::Matrix3d inverse = second.inverse();
      reduced_->setState(centre, spread * inverse, velocity, rate * inverse);
    }
    nodes_stale_ = true;
    return;
  }
  x_ = positions;
  v_ = velocities;
  restartWarmStart();
  rotations_current_ = false;
}

Eigen::VectorXd& Body::mutablePositions() {
  if (reduced_) throw std::logic_error("body '" + name_ + "': its nodes follow its model");
  rotations_current_ = false;  // the caller may move nodes
  return x_;
}

Eigen::VectorXd& Body::mutableVelocities() {
  if (reduced_) throw std::logic_error("body '" + name_ + "': its nodes follow its model");
  return v_;
}

void Body::rememberState() {
  if (reduced_) {
    reduced_->remember();  // its few coordinates, not its nodes
  } else {
    remembered_positions_ = x_;
  }
}

bool Body::stateIsFinite() const {
  return reduced_ ? reduced_->finite() : x_.allFinite() && v_.allFinite();
}

void Body::returnToRememberedState() {
  reaction_.setZero();  // of the undone step
  if (reduced_) {
    reduced_->returnToRemembered();
    nodes_stale_ = true;
    return;
  }
  x_ = remembered_positions_;
  v_.setZero();
  restartWarmStart();
  rotations_current_ = false;
}

const CorotationalElasticity& Body::elasticity() const {
  if (!elasticity_) {
    throw std::logic_error("body '" + name_ + "' is " + modelName(model_) + ": it has no elements");
  }
  return *elasticity_;
}

void Body::updateNodes() const {
  const Eigen::Vector3d rest_centre = reduced_->massProperties().centre;
  const Eigen::Matrix3d& gradient = reduced_->gradient();
  const Eigen::Matrix3d rate = reduced_->gradientRate();
  for (int i = 0; i < numNodes(); ++i) {
    const Eigen::Vector3d arm = x0_.segment<3>(3 * i) - rest_centre;
    x_.segment<3>(3 * i) = reduced_->centre() + gradient * arm;
    v_.segment<3>(3 * i) = reduced_->linearVelocity() + rate * arm;
  }
  nodes_stale_ = false;
  ++node_updates_;
}

NodeConstraints Body::nodeConstraints() const {
  return NodeConstraints{&constrained_nodes_, &x0_, &targets_};
}

void Body::fixNodes(const std::vector<int>& nodes) {
  std::vector<Eigen::Vector3d> here;
  for (int i : nodes) here.emplace_back(positions().segment<3>(3 * i));
  setNodeTargets(nodes, here);
}

void Body::setNodeTargets(const std::vector<int>& nodes,
                          const std::vector<Eigen::Vector3d>& targets) {
  if (nodes.size() != targets.size()) {
    throw std::invalid_argument("body '" + name_ + "': " + std::to_string(nodes.size()) +
                                " nodes but " + std::to_string(targets.size()) + " targets");
  }
  for (size_t k = 0; k < nodes.size(); ++k) {
    if (nodes[k] < 0 || nodes[k] >= numNodes()) {
      throw std::invalid_argument("body '" + name_ + "': node index " + std::to_string(nodes[k]) +
                                  " out of range");
    }
    if (!targets[k].allFinite()) {
      throw std::invalid_argument("body '" + name_ + "': non-finite target for node " +
                                  std::to_string(mesh_.node_numbers[nodes[k]]));
    }
  }
  for (size_t k = 0; k < nodes.size(); ++k) {
    if (!constrained_[nodes[k]]) {
      matrix_changed_ = true;
      if (reduced_) {
        constrained_nodes_.insert(
            std::lower_bound(constrained_nodes_.begin(), constrained_nodes_.end(), nodes[k]),
            nodes[k]);
      }
    }
    constrained_[nodes[k]] = 1;
    targets_.segment<3>(3 * nodes[k]) = targets[k];
  }
}

void Body::releaseNodes(const std::vector<int>& nodes) {
  for (int i : nodes) {
    if (i < 0 || i >= numNodes()) {
      throw std::invalid_argument("body '" + name_ + "': node index " + std::to_string(i) +
                                  " out of range");
    }
    if (constrained_[i]) {
      matrix_changed_ = true;
      if (reduced_) {
        constrained_nodes_.erase(
            std::lower_bound(constrained_nodes_.begin(), constrained_nodes_.end(), i));
      }
    }
    constrained_[i] = 0;
    reaction_.segment<3>(3 * i).setZero();
  }
}

void Body::holdNode(int node) { holdNodeAt(node, positions().segment<3>(3 * node)); }

void Body::holdNodeAt(int node, const Eigen::Vector3d& target) {
  if (reduced_) {  // contact acts on finite-element bodies only; keep the general path
    setNodeTargets({node}, {target});
    return;
  }
  if (!constrained_[node]) matrix_changed_ = true;
  constrained_[node] = 1;
  targets_.segment<3>(3 * node) = target;
}

void Body::releaseNode(int node) {
  if (reduced_) {
    releaseNodes({node});
    return;
  }
  if (constrained_[node]) matrix_changed_ = true;
  constrained_[node] = 0;
  reaction_.segment<3>(3 * node).setZero();
}

void Body::holdNodeOnPlane(int node, const Eigen::Vector3d& normal, const Eigen::Vector3d& target) {
  PlaneHold hold;
  hold.node = node;
  hold.normal = normal;
  hold.offset = normal.dot(target);
  plane_holds_.push_back(hold);
  matrix_changed_ = true;
}

void Body::addStepForce(int node, const Eigen::Vector3d& force) {
  step_forces_.segment<3>(3 * node) += force;
  has_step_forces_ = true;
}

void Body::releasePlaneHolds() {
  if (!plane_holds_.empty()) matrix_changed_ = true;
  for (const PlaneHold& hold : plane_holds_) reaction_.segment<3>(3 * hold.node).setZero();
  plane_holds_.clear();
  if (has_step_forces_) step_forces_.setZero();
  has_step_forces_ = false;
}

void Body::preparePlaneHolds(double dt) {
  if (plane_holds_.empty()) return;
  const RayleighDamping damping = effects_.damping.value_or(RayleighDamping{});
  const double c_m = 1.0 + dt * damping.mass, c_k = dt * damping.stiffness + dt * dt;
  const BlockSparseMatrix& k = elasticity_->stiffness();
  for (PlaneHold& hold : plane_holds_) {
    const int i = hold.node;
    const double diagonal = c_m * mass_[i] + c_k * k.blocks()[k.diagonalIndex(i)].trace() / 3.0;
    hold.stiffness = kPlaneStiffness * diagonal;
    hold.velocity = (hold.offset - hold.normal.dot(x_.segment<3>(3 * i))) / dt;
  }
}

SystemMatrix Body::stepMatrix(double h) const {
  const RayleighDamping damping = effects_.damping.value_or(RayleighDamping{});
  SystemMatrix a = systemMatrix(1.0 + h * damping.mass, h * damping.stiffness + h * h);
  if (!plane_holds_.empty()) a.planes = &plane_holds_;
  return a;
}

SolveReport Body::solveLastStep(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
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

void Body::addConstraintForces(const Eigen::VectorXd& dv) {
  if (!effects_.reactions) return;
  const double h = history_dt_;
  for (const PlaneHold& p : plane_holds_) {  // its spring gives way as the node moves along n
    reaction_.segment<3>(3 * p.node) -=
        p.stiffness * p.normal.dot(dv.segment<3>(3 * p.node)) / h * p.normal;
  }
  if (numConstrained() == 0) return;
  stepMatrix(h).multiply(dv, scratch_);
  for (int i = 0; i < numNodes(); ++i) {
    if (constrained_[i]) reaction_.segment<3>(3 * i) += scratch_.segment<3>(3 * i) / h;
  }
}

int Body::numConstrained() const {
  int count = 0;
  for (std::uint8_t c : constrained_) count += c;
  return count;
}

int Body::updateStiffness(StepTimes* times) {
  const auto start = Clock::now();
  if (effects_.warping && !rotations_current_) {
    const CorotationalElasticity::RotationUpdate update = elasticity_->updateRotations(x_);
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

SystemMatrix Body::systemMatrix(double mass_coefficient, double stiffness_coefficient) const {
  SystemMatrix a;
  a.stiffness = &elasticity_->stiffness();
  a.nodal_mass = &mass_;
  a.mass_coefficient = mass_coefficient;
  a.stiffness_coefficient = stiffness_coefficient;
  a.positions = &x_;
  a.threads = solver_settings_.threads;
  return a;
}

SolveReport Body::solve(const SystemMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                        bool step_start, double reference_floor) {
  if (a.mass_coefficient != last_mass_coefficient_ ||
      a.stiffness_coefficient != last_stiffness_coefficient_) {
    matrix_changed_ = true;
    last_mass_coefficient_ = a.mass_coefficient;
    last_stiffness_coefficient_ = a.stiffness_coefficient;
  }
  SolveReport report;
  if (solver_settings_.method == SolverSettings::Method::kDirect) {
    report = direct_->solve(a, constrained_, b, matrix_changed_, x);
  } else {
    report = cg_.solve(a, constrained_, b, solver_settings_, x, step_start, reference_floor);
  }
  matrix_changed_ = false;
  return report;
}

void Body::restartWarmStart() {
  history_size_ = 0;
  cg_.clearPreviousSolutions();
}

void Body::predictVelocity(Eigen::VectorXd& guess) const {
  // The projected warm start replaces this guess once the solver has solutions to combine.
  const int order =
      solver_settings_.warm_start == SolverSettings::WarmStart::kLastVelocity ? 0 : history_size_;
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

double Body::setStepRightHandSide(double h) {
  // b = M v - h (K' x + f0' - f_ext - M g); K' x on the solver's threads.
  systemMatrix(0.0, 1.0).multiply(x_, scratch_);
  const Eigen::VectorXd& f0 = elasticity_->forceOffset();
  double free_load2 = 0.0;
  for (int i = 0; i < numNodes(); ++i) {
    Eigen::Vector3d load = external_forces_.segment<3>(3 * i);
    if (effects_.gravity) load += mass_[i] * *effects_.gravity;
    if (plasticity_) load += plastic_forces_.segment<3>(3 * i);
    if (has_step_forces_) load += step_forces_.segment<3>(3 * i);
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

StepReport Body::step(double dt) {
  if (reduced_) return stepReduced(dt);
  StepReport report;
  const auto start = Clock::now();
  report.inverted_elements = updateStiffness(&report.times);
  if (plasticity_) {
    plasticity_->step(mesh_, *elasticity_, x_, dt, plastic_forces_);
    ++counters_.plasticity;
  }
  if (effects_.damping) ++counters_.damping;
  if (effects_.gravity) ++counters_.gravity;
  if (effects_.warping) ++counters_.warping;
  if (effects_.reactions) ++counters_.reactions;
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

void Body::advance(double h, int depth, StepReport& report) {
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
  for (int solves = 1;; ++solves) {
    solveVelocity(a, h, solves == 1, report);
    if (!effects_.warping) break;
    const CorotationalElasticity::RotationUpdate end = rotateToEnd(h, report);
    if (solver_settings_.max_rotation_updates == 0) break;
    const EnergyCheck check = checkRotationEnergy(a, end, settling);
    if (!check.gains) break;
    // Converging, the excess shrinks several times over from one solve to the next; where it
    // does not, more solves will not settle it either.
    const bool stalled = check.excess > 0.5 * settling.last_excess;
    settling.last_excess = check.excess;
    if (report.solves >= kMaxSolves) break;  // keep the last solution: a step's time is bounded
    if (stalled || solves > solver_settings_.max_rotation_updates) {
      if (depth >= kMaxSplits) break;
      // Start again from x in two halves; the rotations now are those of a discarded end.
      rotations_current_ = false;
      elastic_energy_ = settling.start_energy;
      ++report.splits;
      advance(0.5 * h, depth + 1, report);
      advance(0.5 * h, depth + 1, report);
      return;
    }
    const auto assembly_start = Clock::now();
    elasticity_->assemble();
    matrix_changed_ = true;
    settling.product_is_current = false;
    settling.solve_start_energy = elasticity_->elasticEnergy(x_);
    report.times.assembly += secondsSince(assembly_start);
  }
  finishAdvance(a, h, settling.product_is_current);
}

void Body::solveVelocity(const SystemMatrix& a, double h, bool step_start, StepReport& report) {
  // Where the loads balance the elastic forces (a body at rest), b is what rounding leaves of
  // them: CG's residual is measured against the loads' impulse there instead.
  const double load_impulse = setStepRightHandSide(h);
  const auto solve_start = Clock::now();
  const SolveReport solved = solve(a, rhs_, next_, step_start, load_impulse);
  report.times.solve += secondsSince(solve_start);
  report.times.preconditioner += solved.preconditioner_seconds;
  report.solve.iterations += solved.iterations;
  report.solve.relative_residual = solved.relative_residual;
  report.solve.converged = solved.converged;
  ++report.solves;
}

CorotationalElasticity::RotationUpdate Body::rotateToEnd(double h, StepReport& report) {
  end_positions_ = x_ + h * next_;
  const auto rotations_start = Clock::now();
  const CorotationalElasticity::RotationUpdate end = elasticity_->updateRotations(end_positions_);
  report.times.rotations += secondsSince(rotations_start);
  end_inverted_elements_ = end.inverted;
  elastic_energy_ = end.energy;
  report.largest_rotation_change = end.largest_change;
  return end;
}

Body::EnergyCheck Body::checkRotationEnergy(const SystemMatrix& a,
                                            const CorotationalElasticity::RotationUpdate& end,
                                            RotationSettling& settling) {
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
  const double roundoff =
      1e-12 * (settling.start_energy + end.energy + 0.5 * start_kinetic2 + 0.5 * kinetic2);
  double dissipated = 0.5 * velocity_change2;
  if (gained > dissipated + roundoff) {
    a.multiply(next_, scratch_);
    settling.product_is_current = true;
    dissipated += 0.5 * (next_.dot(scratch_) - a.mass_coefficient * kinetic2);
  }
  return {gained > dissipated + roundoff, gained - dissipated};
}

void Body::finishAdvance(const SystemMatrix& a, double h, bool product_is_current) {
  // A v+ - b = h (M (v+ - v) / h - f_ext - f_elastic - f_damping): h times the constraint force.
  if (effects_.reactions) {
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
  if (effects_.warping) {
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
  history_dt_ = h;
}

StaticReport Body::solveStatic(const StaticSettings& settings) {
  if (settings.load_steps < 1 || settings.max_iterations < 1 || !(settings.tolerance > 0.0)) {
    throw std::invalid_argument("body '" + name_ +
                                "': static settings need load_steps >= 1, max_iterations >= 1 "
                                "and tolerance > 0");
  }
  if (reduced_) return solveStaticReduced(settings);
  StaticReport report;
  if (effects_.warping) ++counters_.warping;
  const SystemMatrix a = systemMatrix(0.0, 1.0);
  Eigen::VectorXd load = external_forces_;
  if (effects_.gravity) {
    for (int i = 0; i < numNodes(); ++i) load.segment<3>(3 * i) += mass_[i] * *effects_.gravity;
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
      if (!effects_.warping || report.last_change <= settings.tolerance) break;
    }
    report.converged = report.last_solve.converged &&
                       (!effects_.warping || report.last_change <= settings.tolerance);
  }
  v_.setZero();
  restartWarmStart();
  setStaticReactions(load);
  return report;
}

double Body::staticIteration(const SystemMatrix& a, const Eigen::VectorXd& load,
                             const Eigen::VectorXd& start, double fraction, StaticReport& report) {
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

void Body::relaxTowardsNext(double relaxation) {
  for (int i = 0; i < numNodes(); ++i) {
    x_.segment<3>(3 * i) =
        constrained_[i]
            ? Eigen::Vector3d(next_.segment<3>(3 * i))
            : Eigen::Vector3d(x_.segment<3>(3 * i) +
                              relaxation * (next_.segment<3>(3 * i) - x_.segment<3>(3 * i)));
  }
  rotations_current_ = false;
}

void Body::setStaticReactions(const Eigen::VectorXd& load) {
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

StepReport Body::stepReduced(double dt) {
  StepReport report;
  const auto start = Clock::now();
  sumLoads();
  const RayleighDamping damping = effects_.damping.value_or(RayleighDamping{});
  if (effects_.damping) ++counters_.damping;
  if (effects_.gravity) ++counters_.gravity;
  if (effects_.warping && model_ == BodyModel::kPseudoRigid) ++counters_.warping;
  if (effects_.reactions) ++counters_.reactions;
  reduced_->step(dt, load_resultant_, effects_.gravity, damping.mass, damping.stiffness,
                 nodeConstraints(), effects_.reactions ? &reaction_ : nullptr);
  nodes_stale_ = true;
  report.solves = 1;
  report.times.total = report.times.solve = secondsSince(start);
  return report;
}

StaticReport Body::solveStaticReduced(const StaticSettings& settings) {
  sumLoads();
  StaticReport report;
  const int iterations =
      reduced_->solveStatic(load_resultant_, effects_.gravity, nodeConstraints(),
                            settings.max_iterations, settings.tolerance, reaction_);
  report.iterations = std::abs(iterations);
  report.converged = iterations > 0;
  nodes_stale_ = true;
  return report;
}

void Body::sumLoads() {
  if (!loads_stale_) return;
  // Summed when they change, not every step: the step's cost does not depend on the mesh.
  const Eigen::Vector3d rest_centre = reduced_->massProperties().centre;
  load_resultant_ = LoadResultant{};
  for (int i = 0; i < numNodes(); ++i) {
    const Eigen::Vector3d f = external_forces_.segment<3>(3 * i);
    load_resultant_.force += f;
    load_resultant_.first_moment += f * (x0_.segment<3>(3 * i) - rest_centre).transpose();
  }
  loads_stale_ = false;
  ++load_sums_;
}

double Body::kineticEnergy() const {
  if (reduced_) return reduced_->kineticEnergy();
  double energy = 0.0;
  for (int i = 0; i < numNodes(); ++i)
    energy += 0.5 * mass_[i] * v_.segment<3>(3 * i).squaredNorm();
  return energy;
}

double Body::elasticEnergy() const {
  if (reduced_) return reduced_->elasticEnergy();
  if (effects_.warping && rotations_current_) return elastic_energy_;  // computed with them
  return elasticity_->elasticEnergy(x_);
}

}  // namespace deformable_sim::core
