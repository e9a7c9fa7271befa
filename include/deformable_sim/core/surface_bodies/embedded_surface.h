// The user's surface carried by the grid it was voxelized into: every vertex keeps the cell that
// holds it and its trilinear coordinates there, so it moves with the cell's eight nodes (an
// affine motion of the grid moves it exactly). This is what a body made from a surface is drawn
// with; the grid only computes.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "deformable_sim/core/geometry/surface_point.h"
#include "deformable_sim/core/geometry/triangle_mesh.h"
#include "deformable_sim/core/surface_bodies/voxelization.h"

namespace deformable_sim::core {

/// The weights of a hexahedron's eight nodes (Gmsh order) at local coordinates t (0..1 per axis
/// across the cell; outside that range they extrapolate, still exactly for affine motions).
std::array<double, 8> trilinearWeights(const Eigen::Vector3d& t);

class EmbeddedSurface {
 public:
  /// Embeds every vertex of `surface` in the cell of `voxels` that holds it or, when that cell
  /// holds no material (a vertex just outside the cells kept), in the nearest kept cell.
  EmbeddedSurface(TriangleMesh surface, const Voxelization& voxels);

  /// Vertex positions and normals from the grid's node positions x (3 per node). Allocates
  /// nothing.
  void update(const Eigen::VectorXd& x);

  int numVertices() const { return static_cast<int>(rest_.size()); }
  const std::vector<Eigen::Vector3i>& triangles() const { return triangles_; }
  const std::vector<Eigen::Vector3d>& restPositions() const { return rest_; }   ///< m
  const std::vector<Eigen::Vector3d>& positions() const { return positions_; }  ///< m, at update
  /// Per vertex, the unit mean of its triangles' normals weighted by their areas.
  const std::vector<Eigen::Vector3d>& normals() const { return normals_; }
  int cellOf(int vertex) const { return embeddings_[vertex].cell; }  ///< index in Mesh::cells
  const std::array<double, 8>& weights(int vertex) const { return embeddings_[vertex].weights; }
  /// The grid nodes the vertex moves with, in the order of weights().
  const std::array<int, 8>& nodes(int vertex) const { return embeddings_[vertex].nodes; }
  /// The largest node index a vertex depends on (for checking it against a body's mesh).
  int largestNode() const { return largest_node_; }

 private:
  struct Embedding {
    int cell = -1;
    std::array<int, 8> nodes{};
    std::array<double, 8> weights{};
  };
  void updateNormals();

  std::vector<Eigen::Vector3i> triangles_;
  std::vector<Eigen::Vector3d> rest_, positions_, normals_;
  std::vector<Embedding> embeddings_;
  int largest_node_ = -1;
};

/// Vertex v as a point of the grid: the nodes of its cell that carry weight (a vertex on a face
/// or an edge of its cell has fewer than eight); it shifts its cells (SurfacePoint).
SurfacePoint vertexPoint(const EmbeddedSurface& surface, int v);

/// Embeds `surface` in a mesh that voxelize made (hexahedral cubes of one size on a grid, node 0
/// of each its lowest corner): a surface body's mesh read back from a recording. Throws
/// std::invalid_argument naming `what` when the mesh is not such a grid.
EmbeddedSurface embedInGrid(TriangleMesh surface, const Mesh& grid_mesh, const std::string& what);

}  // namespace deformable_sim::core
