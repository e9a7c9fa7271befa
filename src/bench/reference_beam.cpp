#include "deformable_sim/bench/reference_beam.h"

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "deformable_sim/core/elements/selection.h"
#include "deformable_sim/core/geometry/triangle_mesh.h"
#include "deformable_sim/core/surface_bodies/voxelization.h"
#include "deformable_sim/io/mesh_reader.h"

namespace deformable_sim::bench {

namespace {

constexpr double kLength = 1.0;     // L, m
constexpr double kSection = 0.1;    // b = h, m
constexpr double kWeightSum = 1.0;  // tip_load_unit.csv shares a unit load

// Node numbers, one per line, after '#' comments (fix_nodes.txt).
std::vector<long> readNodeList(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read");
  std::vector<long> nodes;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    nodes.push_back(std::stol(line));
  }
  if (nodes.empty()) throw std::runtime_error(path + ": no node");
  return nodes;
}

// "node,weight" lines after '#' comments (tip_load_unit.csv).
void readTipShares(const std::string& path, std::vector<long>& nodes,
                   std::vector<double>& weights) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read");
  std::string line;
  double sum = 0.0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const size_t comma = line.find(',');
    if (comma == std::string::npos) throw std::runtime_error(path + ": not node,weight: " + line);
    nodes.push_back(std::stol(line.substr(0, comma)));
    weights.push_back(std::stod(line.substr(comma + 1)));
    sum += weights.back();
  }
  if (nodes.empty() || std::abs(sum - kWeightSum) > 1e-9) {
    throw std::runtime_error(path + ": the tip shares must sum to 1");
  }
}

// The beam's six faces, turned about the x axis, as a closed surface facing outwards.
core::TriangleMesh turnedBeamSurface(double turn_degrees) {
  const Eigen::AngleAxisd turn(turn_degrees * M_PI / 180.0, Eigen::Vector3d::UnitX());
  core::TriangleMesh surface =
      core::boxSurface(Eigen::Vector3d(0.0, -0.5 * kSection, -0.5 * kSection),
                       Eigen::Vector3d(kLength, 0.5 * kSection, 0.5 * kSection));
  for (Eigen::Vector3d& v : surface.vertices) v = turn * v;
  return surface;
}

// The nodes whose rest x lies within 1e-9 m of `x`.
std::vector<int> nodesAtX(const core::Mesh& mesh, double x) {
  core::NodeSelection plane;
  plane.kind = core::NodeSelection::Kind::kBox;
  plane.box = {Eigen::Vector3d(x - 1e-9, -1.0, -1.0), Eigen::Vector3d(x + 1e-9, 1.0, 1.0)};
  return core::selectNodes(mesh, plane);
}

}  // namespace

bool ReferenceBeam::parseSurfaceId(const std::string& id, double* turn_degrees, int* cells) {
  static const std::regex pattern(R"(surface([0-9.]+)_c([0-9]+))");
  std::smatch match;
  if (!std::regex_match(id, match, pattern)) return false;
  *turn_degrees = std::stod(match[1]);
  *cells = std::stoi(match[2]);
  return true;
}

ReferenceBeam ReferenceBeam::fromSurface(double turn_degrees, int cells) {
  const core::TriangleMesh surface = turnedBeamSurface(turn_degrees);
  core::VoxelSettings settings;
  settings.longest_side_cells = cells;
  ReferenceBeam beam;
  std::ostringstream id;
  id << "surface" << turn_degrees << "_c" << cells;
  beam.id_ = id.str();
  beam.mesh_ = core::voxelize(surface, core::voxelGridFor(surface, settings), settings.levels).mesh;
  beam.clamp_ = nodesAtX(beam.mesh_, 0.0);
  beam.tip_ = nodesAtX(beam.mesh_, kLength);
  beam.tip_weights_.assign(beam.tip_.size(), 1.0 / beam.tip_.size());
  return beam;
}

core::LinearElasticMaterial referenceMaterial() { return {1.0e6, 0.3, 1000.0}; }

double referenceBendingStiffness() {
  const double second_moment = kSection * kSection * kSection * kSection / 12.0;
  return referenceMaterial().youngs_modulus * second_moment;
}

double largeDeflectionLoad(double alpha) {
  return alpha * referenceBendingStiffness() / (kLength * kLength);
}

ReferenceBeam::ReferenceBeam(const std::string& reference_dir, const std::string& mesh_id)
    : id_(mesh_id) {
  const std::string dir = reference_dir + "/meshes/" + mesh_id + "/";
  io::MeshReadResult read = io::readGmsh(dir + mesh_id + ".msh");
  if (!read.warnings.empty()) {
    // The shipped meshes are clean; a repair would mean node numbers no longer match CalculiX's.
    throw std::runtime_error(dir + mesh_id + ".msh: " + read.warnings.front());
  }
  mesh_ = std::move(read.mesh);
  try {
    clamp_ = core::nodeIndices(mesh_, readNodeList(dir + "fix_nodes.txt"));
    std::vector<long> tip_numbers;
    readTipShares(dir + "tip_load_unit.csv", tip_numbers, tip_weights_);
    tip_ = core::nodeIndices(mesh_, tip_numbers);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(dir + ": " + e.what());
  }
}

core::FiniteElementBody ReferenceBeam::makeBeamBody(const core::BodyEffects& effects,
                                                    const core::SolverSettings& solver) const {
  core::FiniteElementBody body(id_, mesh_, referenceMaterial(), effects, solver);
  body.fixNodes(clamp_);
  return body;
}

void ReferenceBeam::applyTipLoad(core::Body& body, double load_n) const {
  body.externalForces().setZero();
  for (size_t k = 0; k < tip_.size(); ++k) {
    body.externalForces()[3 * tip_[k] + 2] = -load_n * tip_weights_[k];
  }
}

Eigen::Vector3d ReferenceBeam::tipDisplacement(const core::Body& body) const {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < tip_.size(); ++k) {
    const int i = tip_[k];
    mean += tip_weights_[k] *
            (body.positions().segment<3>(3 * i) - body.restPositions().segment<3>(3 * i));
  }
  return mean;
}

}  // namespace deformable_sim::bench
