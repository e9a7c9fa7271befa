// Fuzz target: surface files into a grid. The bytes are read by the surface mesh reader (assimp,
// from memory), checked and repaired (core/surface_bodies/surface_check.h), voxelized on a small
// grid and embedded, as a scene's `mesh: {surface: ..}` body is made.
//
// Input: an OBJ when the first byte opens an OBJ statement or comment ('v', 'f', 'o', 'g', 'l',
// 'm', 'u', '#'), else an STL, ascii or binary as assimp tells them apart ("solid" and text, or
// 84 + 50 n bytes). The reader may only throw TriangleMeshError and the body may only be refused
// with std::invalid_argument, each with a message. What the reader gives has finite vertices,
// valid indices and no triangle with a corner twice; the check, run again on what it returned,
// drops nothing; the body's cells have octant fractions in [0, 1], a finite mass > 0 no greater
// than its grid's, and its embedded surface keeps the checked surface's vertices and triangles.
// The grid has at most kCells cells along its longest side. Corpus: test/fuzz/corpus/fuzz_surfaces.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/core/surface_bodies/surface_body.h"
#include "deformable_sim/core/surface_bodies/surface_check.h"
#include "deformable_sim/io/triangle_mesh_reader.h"
#include "fuzz_checks.h"

namespace deformable_sim::fuzz {
namespace {

constexpr int kCells = 5;  // along the longest side: at most 125 cells, a run stays fast

void requireValidSurface(const core::TriangleMesh& mesh, const std::string& what) {
  const int n = static_cast<int>(mesh.vertices.size());
  for (const Eigen::Vector3d& v : mesh.vertices) {
    require(v.allFinite(), what + ": a non-finite vertex");
  }
  for (const Eigen::Vector3i& t : mesh.triangles) {
    require((t.array() >= 0).all() && (t.array() < n).all(), what + ": index out of range");
    require(t[0] != t[1] && t[1] != t[2] && t[2] != t[0], what + ": a corner twice");
  }
}

void requireMessage(const std::exception& e, const std::string& what) {
  require(std::strlen(e.what()) > 0, what + " without a message");
}

// The cells of `body`: fractions in [0, 1] and a mass (density 1) in (0, grid volume].
void requireValidBody(const core::SurfaceBody& body) {
  const core::Mesh& mesh = body.voxels.mesh;
  require(!mesh.cells.empty(), "a body without cells");
  require(mesh.cell_fractions.size() == mesh.cells.size(), "a fraction per cell");
  require(static_cast<long>(mesh.cells.size()) <= kCells * kCells * kCells, "grid over the cap");
  for (const core::OctantFractions& octants : mesh.cell_fractions) {
    for (double f : octants) require(f >= 0.0 && f <= 1.0, "a fraction outside [0, 1]");
  }
  const double mass = core::totalVolume(mesh);
  const double h = body.voxels.grid.cell_size;
  const double grid_volume = static_cast<double>(mesh.cells.size()) * h * h * h;
  require(std::isfinite(mass) && mass > 0.0, "a body's mass not finite and > 0");
  require(mass <= grid_volume * (1.0 + 1e-9), "a body heavier than its cells");
}

// Reads `bytes`, or returns false when the reader refuses them (as documented).
bool read(const std::string& bytes, core::TriangleMesh& mesh, int& collapsed) {
  const char first = bytes.empty() ? '\0' : bytes[0];
  const bool obj = std::string("vfoglmu#").find(first) != std::string::npos && first != '\0';
  try {
    mesh = io::readTriangleMeshFromMemory(bytes, obj ? "obj" : "stl", obj ? "fuzz.obj" : "fuzz.stl",
                                          Eigen::Vector3d::Ones(), &collapsed);
  } catch (const io::TriangleMeshError& e) {
    requireMessage(e, "a reader's refusal");
    return false;
  }
  require(!mesh.triangles.empty(), "the reader accepted a surface without triangles");
  require(collapsed >= 0, "a negative count of collapsed triangles");
  requireValidSurface(mesh, "from the reader");
  return true;
}

}  // namespace

void fuzzSurfaces(const uint8_t* data, std::size_t size) {
  core::TriangleMesh mesh;
  int collapsed = 0;
  if (!read(std::string(reinterpret_cast<const char*>(data), size), mesh, collapsed)) return;
  core::TriangleMesh checked = mesh;
  core::checkSurface(checked, collapsed);
  requireValidSurface(checked, "from the check");
  core::TriangleMesh again = checked;
  const core::SurfaceCheck second = core::checkSurface(again);
  require(second.zero_area == 0 && second.duplicates == 0, "the check dropped more a second time");
  core::VoxelSettings settings;
  settings.longest_side_cells = kCells;
  settings.levels = 2;  // an octant cut again once: reaches the recursion, stays cheap
  std::vector<std::string> warnings;
  try {
    const core::SurfaceBody body = core::bodyFromSurface(mesh, settings, &warnings, collapsed);
    requireValidBody(body);
    require(body.surface.numVertices() == static_cast<int>(checked.vertices.size()) &&
                body.surface.triangles() == checked.triangles,
            "the embedded surface is not the checked one");
  } catch (const std::invalid_argument& e) {
    requireMessage(e, "a refused body");
    return;
  }
  for (const std::string& w : warnings) require(!w.empty(), "an empty warning");
}

}  // namespace deformable_sim::fuzz

DEFORMABLE_SIM_FUZZ_TARGET(deformable_sim::fuzz::fuzzSurfaces)
