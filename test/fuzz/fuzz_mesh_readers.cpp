// Fuzz target: the mesh readers (Gmsh .msh 2.2 and 4.1, TetGen .node/.ele), read from memory.
//
// Input: a Gmsh file when it starts with '$'; otherwise a TetGen pair, the .node file, then a line
// "%%ele", then the .ele file. A reader may only throw MeshError. What it accepts must be a valid
// mesh (finite nodes, each used, elements of positive volume on known nodes) that builds a body,
// and a small one is stepped: its state must stay finite. Corpus:
// test/fuzz/corpus/fuzz_mesh_readers.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "deformable_sim/core/bodies/body.h"
#include "deformable_sim/core/elements/cell.h"
#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/io/mesh_reader.h"
#include "fuzz_checks.h"

namespace deformable_sim::fuzz {
namespace {

constexpr char kElementSeparator[] = "\n%%ele\n";
constexpr int kMaxSteppedTetrahedra = 64;  // larger meshes are only read: keep runs fast

void requireValidMesh(const core::Mesh& mesh) {
  require(mesh.numElements() > 0, "accepted a mesh without elements");
  require(mesh.node_numbers.size() == mesh.positions.size(),
          "node numbers and positions differ in count");
  std::vector<bool> used(mesh.positions.size(), false);
  for (const core::Tetrahedron& tet : mesh.tetrahedra) {
    for (int k = 0; k < 4; ++k) {
      require(tet[k] >= 0 && tet[k] < mesh.numNodes(), "node index out of range");
      for (int j = 0; j < k; ++j) require(tet[j] != tet[k], "a node twice in a tetrahedron");
      used[tet[k]] = true;
    }
    require(core::signedVolume(mesh.positions, tet) > 0.0, "accepted a non-positive volume");
  }
  for (const core::Cell& cell : mesh.cells) {
    for (int k = 0; k < cell.size(); ++k) {
      require(cell.nodes[k] >= 0 && cell.nodes[k] < mesh.numNodes(), "node index out of range");
      for (int j = 0; j < k; ++j) require(cell.nodes[j] != cell.nodes[k], "a node twice in a cell");
      used[cell.nodes[k]] = true;
    }
    require(core::jacobianRange(cell.type, core::cellCorners(cell, mesh.positions)).first > 0.0,
            "accepted a cell with a non-positive Jacobian");
  }
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    require(mesh.positions[i].allFinite(), "accepted a non-finite coordinate");
    require(used[i], "kept a node that no element uses");
  }
}

// A body of the mesh falls under gravity for a few steps.
void simulate(const core::Mesh& mesh) {
  core::BodyEffects effects;
  effects.warping = true;
  effects.gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
  effects.damping = core::RayleighDamping{1.0, 0.002};
  core::SceneSpec spec;
  core::BodySpec body;
  body.name = "fuzz";
  spec.effects = effects;
  spec.bodies.push_back(body);
  std::vector<core::Mesh> meshes{mesh};
  try {
    core::Simulation simulation(spec, std::move(meshes));
    stepAndCheck(simulation, 3, "mesh from the reader");
  } catch (const std::invalid_argument& e) {
    finding(std::string("the reader accepted a mesh that makes no body: ") + e.what());
  }
}

}  // namespace

void fuzzMeshReaders(const uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  io::MeshReadResult result;
  try {
    if (!text.empty() && text[0] == '$') {
      std::istringstream stream(text);
      result = io::readGmsh(stream, "fuzz.msh");
    } else {
      const std::size_t split = text.find(kElementSeparator);
      std::istringstream nodes(text.substr(0, split));
      std::istringstream elements(
          split == std::string::npos ? "" : text.substr(split + sizeof kElementSeparator - 1));
      result = io::readTetGen(nodes, elements, "fuzz");
    }
  } catch (const io::MeshError&) {
    return;  // refused, as documented
  }
  requireValidMesh(result.mesh);
  if (result.mesh.numTetrahedra() <= kMaxSteppedTetrahedra) simulate(result.mesh);
}

}  // namespace deformable_sim::fuzz

DEFORMABLE_SIM_FUZZ_TARGET(deformable_sim::fuzz::fuzzMeshReaders)
