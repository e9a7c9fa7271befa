#include "deformable_sim/core/simulation.h"

#include <stdexcept>

#include "deformable_sim/core/loads.h"
#include "deformable_sim/core/selection.h"

namespace deformable_sim::core {

namespace {

std::vector<int> selectSome(const Mesh& mesh, const NodeSelection& selection,
                            const std::string& key) {
  std::vector<int> nodes;
  try {
    nodes = selectNodes(mesh, selection);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(key + ": " + e.what());
  }
  if (nodes.empty()) throw std::invalid_argument(key + ": selects no node");
  return nodes;
}

}  // namespace

Simulation::Simulation(const SceneSpec& spec, std::vector<Mesh> meshes)
    : dt_(spec.dt), statics_(spec.statics) {
  if (!(spec.dt > 0.0) || !std::isfinite(spec.dt)) {
    throw std::invalid_argument("dt: must be finite and > 0 s");
  }
  if (meshes.size() != spec.bodies.size()) {
    throw std::invalid_argument("bodies: " + std::to_string(spec.bodies.size()) +
                                " bodies but " + std::to_string(meshes.size()) + " meshes");
  }
  bodies_.reserve(spec.bodies.size());
  for (size_t b = 0; b < spec.bodies.size(); ++b) {
    const BodySpec& body_spec = spec.bodies[b];
    const std::string key = "bodies[" + std::to_string(b) + "]";
    try {
      bodies_.emplace_back(body_spec.name, std::move(meshes[b]), body_spec.material, spec.effects,
                           spec.solver);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(key + ": " + e.what());
    }
    FemBody& body = bodies_.back();
    for (size_t k = 0; k < body_spec.fixed.size(); ++k) {
      body.fixNodes(selectSome(body.mesh(), body_spec.fixed[k],
                               key + ".fixed[" + std::to_string(k) + "]"));
    }
    const std::vector<Triangle> surface = extractSurface(body.mesh());
    for (size_t k = 0; k < body_spec.loads.size(); ++k) {
      const LoadSpec& load = body_spec.loads[k];
      const std::string load_key = key + ".loads[" + std::to_string(k) + "]";
      if (!load.value.allFinite()) throw std::invalid_argument(load_key + ": non-finite value");
      const std::vector<int> nodes = selectSome(body.mesh(), load.where, load_key);
      if (load.kind == LoadSpec::Kind::kTotalForce) {
        addTotalForce(nodes, load.value, body.externalForces());
      } else if (addTractionLoad(body.mesh(), surface, nodes, load.value, body.externalForces()) ==
                 0.0) {
        throw std::invalid_argument(load_key +
                                    ": traction selects no boundary face (all three nodes of a "
                                    "surface triangle must be selected)");
      }
    }
  }
}

FemBody& Simulation::body(const std::string& name) {
  for (FemBody& b : bodies_) {
    if (b.name() == name) return b;
  }
  throw std::out_of_range("no body named '" + name + "'");
}

void Simulation::step(std::vector<StepReport>& reports) {
  reports.resize(bodies_.size());
  for (size_t b = 0; b < bodies_.size(); ++b) reports[b] = bodies_[b].step(dt_);
  ++step_count_;
}

std::vector<StaticReport> Simulation::solveStatic() {
  std::vector<StaticReport> reports;
  for (FemBody& b : bodies_) reports.push_back(b.solveStatic(statics_));
  return reports;
}

}  // namespace deformable_sim::core
