// A volumetric mesh: rest positions, the mesh file's own node numbers, connectivity (linear
// tetrahedra, plus the pyramids, wedges and hexahedra of seed 004), and the geometric queries
// every body needs (volumes, boundary, lumped mass).
#pragma once

#include <Eigen/Core>
#include <array>
#include <map>
#include <string>
#include <vector>

namespace deformable_sim::core {

/// Four node indices into Mesh::positions, ordered so that
/// (x1 - x0) x (x2 - x0) . (x3 - x0) > 0 (positive volume).
using Tetrahedron = std::array<int, 4>;

/// Three node indices of a boundary triangle, counter-clockwise seen from outside.
using Triangle = std::array<int, 3>;

/// The element types besides the tetrahedron; the value is the number of nodes.
enum class CellType { kPyramid = 5, kWedge = 6, kHexahedron = 8 };

/// A pyramid, wedge or hexahedron: its first size() entries index Mesh::positions, in Gmsh's
/// order (the base counter-clockwise seen from the apex or the opposite face, then that face).
struct Cell {
  CellType type = CellType::kHexahedron;
  std::array<int, 8> nodes{};
  int size() const { return static_cast<int>(type); }
};

/// A boundary face, counter-clockwise seen from outside: a triangle, or a quadrilateral when
/// nodes[3] >= 0.
struct Face {
  std::array<int, 4> nodes{-1, -1, -1, -1};
  int size() const { return nodes[3] >= 0 ? 4 : 3; }
};

/// The material fractions of a cell's eight octants, each in [0, 1]: the parts of the natural
/// cube with xi_k below or above 0, octant (xi1 > 0) + 2 (xi2 > 0) + 4 (xi3 > 0). A hexahedron of
/// a grid cut by a surface (core/surface_bodies/voxelization.h) weighs and resists where its
/// material is; other cell types take the mean throughout.
using OctantFractions = std::array<double, 8>;

struct Mesh {
  std::vector<Eigen::Vector3d> positions;  ///< rest positions, m
  std::vector<long> node_numbers;          ///< the file's number of each node (same order)
  std::vector<Tetrahedron> tetrahedra;
  /// The other elements, kept apart from the tetrahedra, which have a closed-form fast path.
  std::vector<Cell> cells;
  /// Hexahedra with incompatible modes (core/elements/incompatible_modes.h) instead of plain full
  /// integration, where their material allows (incompatibleModesApply): a voxel grid's, a few
  /// cells through a part, which would lock in bending.
  bool incompatible_modes = false;
  /// Per cell, the part of each octant that holds material. Empty: every cell is full.
  std::vector<OctantFractions> cell_fractions;
  /// Named node groups (indices into positions), e.g. from the scene's `groups`.
  std::map<std::string, std::vector<int>> groups;

  /// The material fraction of cells[c], the mean of its octants': 1 without cell_fractions.
  double cellFraction(size_t c) const;
  /// Its octants' fractions, or null without cell_fractions (all full).
  const OctantFractions* cellOctants(size_t c) const {
    return cell_fractions.empty() ? nullptr : &cell_fractions[c];
  }

  int numNodes() const { return static_cast<int>(positions.size()); }
  int numTetrahedra() const { return static_cast<int>(tetrahedra.size()); }
  int numElements() const { return numTetrahedra() + static_cast<int>(cells.size()); }
};

/// Signed volume of a tetrahedron with corners a, b, c, d, m^3 (positive when right-handed).
double signedVolume(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                    const Eigen::Vector3d& d);

/// Signed volume of tetrahedron t of the mesh at the given positions, m^3.
double signedVolume(const std::vector<Eigen::Vector3d>& positions, const Tetrahedron& t);

/// Shape quality of tetrahedron t, 6 sqrt(2) V / l^3 with l the root mean square of its six edge
/// lengths: 1 for the regular tetrahedron, 0.66 for those of makeBoxMesh, towards 0 as it
/// flattens, negative when inverted. Scale-free.
double shapeQuality(const std::vector<Eigen::Vector3d>& positions, const Tetrahedron& t);

/// Below this shape quality a tetrahedron counts as a sliver: accepted (its volume is positive),
/// but its stiffness across its thin direction is out of scale with its mass and its neighbours'.
constexpr double kSliverQuality = 0.01;

/// Indices of the tetrahedra whose shape quality is below `min_quality`, ascending. The mesh
/// readers report them as a warning; meshes built in code can be checked with it.
std::vector<int> sliverTetrahedra(const Mesh& mesh, double min_quality = kSliverQuality);

/// Sum of the element volumes at rest (of a cell, of its material), m^3.
double totalVolume(const Mesh& mesh);

/// The faces that belong to exactly one element, oriented with outward normals.
std::vector<Face> extractBoundary(const Mesh& mesh);

/// The boundary as triangles (each quadrilateral split along a diagonal), for drawing.
std::vector<Triangle> extractSurface(const Mesh& mesh);

/// Lumped (diagonal) nodal masses: each element gives node i density x the integral of its shape
/// function N_i (a quarter of the volume for a tetrahedron) over the element's material. density
/// in kg/m^3, result in kg per node.
std::vector<double> lumpedMasses(const Mesh& mesh, double density);

/// Index of each node given by its file number. Throws std::invalid_argument naming the first
/// number that is not a node of the mesh.
std::vector<int> nodeIndices(const Mesh& mesh, const std::vector<long>& node_numbers);

/// Per node, the nodes that share an element with it, itself first, unsorted and repeated: the
/// pattern of a stiffness matrix (core/solvers/block_sparse_matrix.h).
std::vector<std::vector<int>> nodeNeighbours(const Mesh& mesh);

}  // namespace deformable_sim::core
