#include "deformable_sim/core/session/simulation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "deformable_sim/core/base/parallel_for.h"
#include "deformable_sim/core/base/spec_error.h"
#include "deformable_sim/core/bodies/wrench.h"
#include "deformable_sim/core/elements/loads.h"
#include "deformable_sim/core/elements/selection.h"

namespace deformable_sim::core {

namespace {

std::vector<int> selectSome(const Mesh& mesh, const NodeSelection& selection,
                            const std::string& key) {
  std::vector<int> nodes;
  try {
    nodes = selectNodes(mesh, selection);
  } catch (const std::invalid_argument& e) {
    throw SpecError(key, e.what());
  }
  if (nodes.empty()) throw SpecError(key, "selects no node");
  return nodes;
}

void addWrench(Body& body, const std::vector<int>& nodes, const LoadSpec& load,
               const std::string& key) {
  if (!load.torque.allFinite()) throw SpecError(key, "non-finite torque");
  std::vector<Eigen::Vector3d> points, forces;
  std::vector<double> weights;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double total = 0.0;
  for (int i : nodes) {
    points.push_back(body.mesh().positions[i]);
    weights.push_back(body.nodalMasses()[i]);
    centroid += weights.back() * points.back();
    total += weights.back();
  }
  try {
    distributeWrench(points, weights, load.value, load.torque, centroid / total, forces);
  } catch (const std::invalid_argument& e) {
    throw SpecError(key, e.what());
  }
  for (size_t k = 0; k < nodes.size(); ++k)
    body.externalForces().segment<3>(3 * nodes[k]) += forces[k];
}

void addGroups(Mesh& mesh, const BodySpec& body_spec, const std::string& key) {
  for (const auto& [name, selection] : body_spec.groups) {
    if (name.empty() || name.find('/') != std::string::npos) {
      throw SpecError(key + ".groups",
                      "'" + name + "' is not a valid group name (non-empty, no '/')");
    }
    mesh.groups[name] = selectSome(mesh, selection, key + ".groups." + name);
  }
}

void addLoads(Body& body, const BodySpec& body_spec, const std::string& key) {
  const std::vector<Face> boundary = extractBoundary(body.mesh());
  for (size_t k = 0; k < body_spec.loads.size(); ++k) {
    const LoadSpec& load = body_spec.loads[k];
    const std::string load_key = key + ".loads[" + std::to_string(k) + "]";
    if (!load.value.allFinite()) throw SpecError(load_key, "non-finite value");
    const std::vector<int> nodes = selectSome(body.mesh(), load.where, load_key);
    if (load.kind == LoadSpec::Kind::kTotalForce) {
      addTotalForce(nodes, load.value, body.externalForces());
    } else if (load.kind == LoadSpec::Kind::kWrench) {
      addWrench(body, nodes, load, load_key);
    } else if (addTractionLoad(body.mesh(), boundary, nodes, load.value, body.externalForces()) ==
               0.0) {
      throw SpecError(load_key,
                      "traction selects no boundary face (all nodes of a boundary face must be "
                      "selected)");
    }
  }
}

}  // namespace

Simulation::Simulation(const SceneSpec& spec, std::vector<Mesh> meshes)
    : dt_(spec.dt),
      threads_(std::max(1, spec.solver.threads)),
      statics_(spec.statics),
      contact_(spec.contact),
      obstacles_(spec.obstacles) {
  if (contact_ && !(contact_->friction >= 0.0 && std::isfinite(contact_->friction))) {
    throw SpecError("effects.contact.friction", "must be finite and >= 0");
  }
  for (size_t k = 0; k < obstacles_.size(); ++k) {
    validate(obstacles_[k].shape, "obstacles[" + std::to_string(k) + "]");
  }
  if (!(spec.dt > 0.0) || !std::isfinite(spec.dt)) {
    throw SpecError("dt", "must be finite and > 0 s");
  }
  if (meshes.size() != spec.bodies.size()) {
    throw SpecError("bodies", std::to_string(spec.bodies.size()) + " bodies but " +
                                  std::to_string(meshes.size()) + " meshes");
  }
  bodies_.reserve(spec.bodies.size());
  wrench_radii_.reserve(spec.bodies.size());
  for (size_t b = 0; b < spec.bodies.size(); ++b) addBody(spec, b, std::move(meshes[b]));
  if (contact_) contact_step_.emplace(bodies_, *contact_);
  energy_watch_.emplace(bodies_);
}

void Simulation::addBody(const SceneSpec& spec, size_t b, Mesh mesh) {
  const BodySpec& body_spec = spec.bodies[b];
  const std::string key = "bodies[" + std::to_string(b) + "]";
  addGroups(mesh, body_spec, key);
  const BodySettings settings{
      body_spec.model, body_spec.material,
      effectsOf(body_spec.model, spec.effects, body_spec.effects, spec.contact.has_value()),
      spec.solver};
  try {
    bodies_.add(makeBody(body_spec.name, std::move(mesh), settings));
  } catch (const std::invalid_argument& e) {
    throw SpecError(key, e.what());
  }
  Body& body = bodies_.back();
  if (!(body_spec.wrench_radius >= 0.0) || !std::isfinite(body_spec.wrench_radius)) {
    throw SpecError(key + ".wrench_radius", "must be finite and >= 0 m");
  }
  wrench_radii_.push_back(body_spec.wrench_radius);
  recoveries_.push_back(0);
  for (size_t k = 0; k < body_spec.fixed.size(); ++k) {
    body.fixNodes(
        selectSome(body.mesh(), body_spec.fixed[k], key + ".fixed[" + std::to_string(k) + "]"));
  }
  addLoads(body, body_spec, key);
  if (!body_spec.velocity.isZero(0.0)) {
    if (!body_spec.velocity.allFinite()) throw SpecError(key + ".velocity", "must be finite");
    if (numConstrained(body) > 0) {
      throw SpecError(key + ".velocity", "a body with fixed nodes starts at rest");
    }
    body.setState(body.positions(), body_spec.velocity.replicate(body.numNodes(), 1));
  }
}

Body& Simulation::body(const std::string& name) {
  for (Body& b : bodies_) {
    if (b.name() == name) return b;
  }
  throw std::out_of_range("no body named '" + name + "'");
}

int Simulation::bodyIndex(const std::string& name) const {
  for (size_t b = 0; b < bodies_.size(); ++b) {
    if (bodies_[b].name() == name) return static_cast<int>(b);
  }
  return -1;
}

void Simulation::setDt(double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt))
    throw std::invalid_argument("dt: must be finite and > 0 s");
  dt_ = dt;
}

void Simulation::step(std::vector<StepReport>& reports) {
  reports.resize(bodies_.size());
  energy_watch_->before(bodies_, obstacles_, dt_);
  if (contact_step_) contact_step_->begin(obstacles_);
  // Bodies step apart until they meet: on the solver's threads, a body each (a body's own loops
  // then run on one thread; its result is the same bits on any number).
  const int threads = bodies_.size() > 1 ? threads_ : 1;
  parallelFor(threads, 0, static_cast<int>(bodies_.size()),
              [&](int b) { stepBody(b, reports[b]); });
  if (contact_step_) {
    contact_step_->finish(bodies_, obstacles_, dt_, threads, reports);
    for (size_t b = 0; b < bodies_.size(); ++b) {
      // Contact too may be handed what no step can take (a grasp thrown 1e300 m away).
      if (contact_step_->actsOn(static_cast<int>(b)) && !bodies_[b].stateIsFinite()) {
        undoStep(static_cast<int>(b), reports[b]);
        contact_step_->forget(static_cast<int>(b));
      }
    }
  }
  energy_watch_->after(bodies_, dt_, [this](int b) -> const std::vector<ContactLoad>& {
    return obstacleContacts(b);
  });
  for (int b = 0; b < static_cast<int>(bodies_.size()); ++b) {
    if (reports[b].recovered || !energy_watch_->leapt(bodies_[b], b, dt_)) continue;
    undoStep(b, reports[b]);
    reports[b].energy_leapt = true;
    if (contact_step_) contact_step_->forget(b);
  }
  ++step_count_;
  time_ += dt_;
}

void Simulation::stepBody(int b, StepReport& report) {
  Body& body = bodies_[b];
  const double holding = contact_step_ ? contact_step_->hold(b, body, obstacles_, dt_) : 0.0;
  report = body.step(dt_);
  report.times.obstacle_contact = holding;
  // Constraint forces too: a tiny dt (1e-320 s) divides a finite solve into infinite forces.
  if (!std::isfinite(report.solve.relative_residual) || !body.stateIsFinite() ||
      !body.reactionForces().allFinite()) {
    undoStep(b, report);
  }
}

void Simulation::undoStep(int b, StepReport& report) {
  bodies_[b].undoStep();
  report.recovered = true;
  ++recoveries_[b];
}

void Simulation::refuseBodiesInsideEachOther() const {
  const BodyContact* contact = bodyContact();
  if (!contact) return;
  const BodyContact::Overlap overlap = contact->deepestOverlap();
  if (overlap.inside < 0) return;
  const double allowed =
      BodyContact::kStartingOverlap * contact->tolerance(overlap.inside, overlap.of);
  if (!(overlap.depth > allowed)) return;
  const auto mm = [](double m) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", 1e3 * m);
    return std::string(text);
  };
  throw SpecError("bodies[" + std::to_string(overlap.inside) + "]",
                  "body '" + bodies_[overlap.inside].name() + "' starts " + mm(overlap.depth) +
                      " mm inside body '" + bodies_[overlap.of].name() +
                      "'; bodies may start at most " + mm(allowed) +
                      " mm into each other (1 % of the smaller one's size): place them apart");
}

const std::vector<ContactLoad>& Simulation::obstacleContacts(int b) const {
  static const std::vector<ContactLoad> none;
  return contact_step_ ? contact_step_->obstacleContacts(b) : none;
}

std::vector<StaticReport> Simulation::solveStatic() {
  std::vector<StaticReport> reports;
  for (Body& b : bodies_) reports.push_back(b.solveStatic(statics_));
  return reports;
}

const EmbeddedSurface* Simulation::embeddedSurface(int b) const {
  if (b < 0 || b >= static_cast<int>(embedded_surfaces_.size())) return nullptr;
  return embedded_surfaces_[b] ? &*embedded_surfaces_[b] : nullptr;
}

EmbeddedSurface* Simulation::embeddedSurface(int b) {
  if (b < 0 || b >= static_cast<int>(embedded_surfaces_.size())) return nullptr;
  return embedded_surfaces_[b] ? &*embedded_surfaces_[b] : nullptr;
}

void Simulation::setEmbeddedSurface(int b, EmbeddedSurface surface) {
  if (b < 0 || b >= static_cast<int>(bodies_.size())) {
    throw std::invalid_argument("embedded surface: no body " + std::to_string(b));
  }
  if (surface.largestNode() >= bodies_[b].mesh().numNodes()) {
    throw std::invalid_argument("body '" + bodies_[b].name() +
                                "': the embedded surface refers to nodes its mesh does not have");
  }
  embedded_surfaces_.resize(bodies_.size());
  surface.update(bodies_[b].positions());
  // Obstacles and bodies touch the user's surface, not the grid's boundary up to a cell outside.
  if (contact_step_) contact_step_->embed(b, surface, bodies_[b]);
  embedded_surfaces_[b] = std::move(surface);
}

}  // namespace deformable_sim::core
