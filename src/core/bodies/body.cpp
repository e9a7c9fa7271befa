#include "deformable_sim/core/bodies/body.h"

#include <stdexcept>
#include <utility>

#include "deformable_sim/core/bodies/finite_element_body.h"
#include "deformable_sim/core/bodies/reduced_body.h"
#include "deformable_sim/core/elements/cell.h"
#include "deformable_sim/core/elements/parameter_limits.h"

namespace deformable_sim::core {

namespace {

void validateCells(const std::string& where, const Mesh& mesh);
void validateGroups(const std::string& where, const Mesh& mesh);

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
  validateGroups(where, mesh);
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

void validateGroups(const std::string& where, const Mesh& mesh) {
  for (const auto& [name, nodes] : mesh.groups) {
    for (int i : nodes) {
      if (i < 0 || i >= mesh.numNodes()) {
        throw std::invalid_argument(where + "group '" + name + "' has node index " +
                                    std::to_string(i) + " out of range");
      }
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

Body::Body(std::string name, Mesh mesh, const BodySettings& settings)
    : name_(std::move(name)),
      mesh_(std::move(mesh)),
      settings_(settings),
      x0_(stack(validated(name_, mesh_).positions)),
      x_(x0_),
      v_(Eigen::VectorXd::Zero(x0_.size())),
      mass_(lumpedMasses(mesh_, settings.material.density)),
      constrained_(mesh_.numNodes(), 0),
      targets_(x0_),
      external_forces_(Eigen::VectorXd::Zero(x0_.size())),
      reaction_(Eigen::VectorXd::Zero(x0_.size())) {
  try {
    validate(settings.material);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(where() + e.what());
  }
  const SolverSettings& solver = settings.solver;
  checkSolverLimits(solver.tolerance, solver.max_iterations, where());
  if (settings.effects.damping) {
    checkDamping(settings.effects.damping->mass, settings.effects.damping->stiffness, where());
  }
  if (solver.threads < 1 || solver.coarse_refresh_interval < 1) {
    throw std::invalid_argument(where() +
                                "solver threads and coarse_refresh_interval must be >= 1");
  }
}

Body::~Body() = default;

void Body::tune(const BodyTuning& tuning) {
  SolverSettings& solver = settings_.solver;
  const double tolerance = tuning.solver_tolerance.value_or(solver.tolerance);
  const int max_iterations = tuning.solver_max_iterations.value_or(solver.max_iterations);
  try {
    if (tuning.material) validate(*tuning.material);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(where() + e.what());
  }
  if (tuning.damping) checkDamping(tuning.damping->mass, tuning.damping->stiffness, where());
  checkSolverLimits(tolerance, max_iterations, where());
  if (tuning.material) {
    // E, nu and density change; the law is the body's own (a tuning message carries none).
    LinearElasticMaterial material = *tuning.material;
    material.law = settings_.material.law;
    changeMaterial(material);
    settings_.material = material;
    mass_ = lumpedMasses(mesh_, material.density);
  }
  if (tuning.damping) settings_.effects.damping = tuning.damping;
  solver.tolerance = tolerance;
  solver.max_iterations = max_iterations;
}

void Body::setState(const Eigen::VectorXd& positions, const Eigen::VectorXd& velocities) {
  if (positions.size() != x_.size() || velocities.size() != v_.size()) {
    throw std::invalid_argument(where() + "state of the wrong size");
  }
  assignState(positions, velocities);
}

StaticReport Body::solveStatic(const StaticSettings& settings) {
  if (settings.load_steps < 1 || settings.max_iterations < 1 || !(settings.tolerance > 0.0)) {
    throw std::invalid_argument(where() +
                                "static settings need load_steps >= 1, max_iterations >= 1 "
                                "and tolerance > 0");
  }
  return solveStaticChecked(settings);
}

void Body::fixNodes(const std::vector<int>& nodes) {
  std::vector<Eigen::Vector3d> here;
  for (int i : nodes) {  // an index out of range is refused by setNodeTargets, not read
    here.emplace_back(i >= 0 && i < numNodes() ? Eigen::Vector3d(positions().segment<3>(3 * i))
                                               : Eigen::Vector3d::Zero());
  }
  setNodeTargets(nodes, here);
}

void Body::setNodeTargets(const std::vector<int>& nodes,
                          const std::vector<Eigen::Vector3d>& targets) {
  if (nodes.size() != targets.size()) {
    throw std::invalid_argument(where() + std::to_string(nodes.size()) + " nodes but " +
                                std::to_string(targets.size()) + " targets");
  }
  for (size_t k = 0; k < nodes.size(); ++k) {
    if (nodes[k] < 0 || nodes[k] >= numNodes()) {
      throw std::invalid_argument(where() + "node index " + std::to_string(nodes[k]) +
                                  " out of range");
    }
    if (!targets[k].allFinite()) {
      throw std::invalid_argument(where() + "non-finite target for node " +
                                  std::to_string(mesh_.node_numbers[nodes[k]]));
    }
  }
  for (size_t k = 0; k < nodes.size(); ++k) {
    if (!constrained_[nodes[k]]) holdChanged(nodes[k], true);
    constrained_[nodes[k]] = 1;
    targets_.segment<3>(3 * nodes[k]) = targets[k];
  }
}

void Body::releaseNodes(const std::vector<int>& nodes) {
  for (int i : nodes) {  // all checked first: a refused release lets none go
    if (i < 0 || i >= numNodes()) {
      throw std::invalid_argument(where() + "node index " + std::to_string(i) + " out of range");
    }
  }
  for (int i : nodes) {
    if (constrained_[i]) holdChanged(i, false);
    constrained_[i] = 0;
    reaction_.segment<3>(3 * i).setZero();
  }
}

int numConstrained(const Body& body) {
  int count = 0;
  for (int i = 0; i < body.numNodes(); ++i) count += body.isConstrained(i) ? 1 : 0;
  return count;
}

std::unique_ptr<Body> makeBody(std::string name, Mesh mesh, const BodySettings& settings) {
  const BodySettings& s = settings;
  if (s.model == BodyModel::kFiniteElement) {
    return std::make_unique<FiniteElementBody>(std::move(name), std::move(mesh), s.material,
                                               s.effects, s.solver);
  }
  return std::make_unique<ReducedBody>(std::move(name), std::move(mesh), s.material, s.effects,
                                       s.solver, s.model);
}

}  // namespace deformable_sim::core
