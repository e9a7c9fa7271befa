#include "deformable_sim/core/geometry/triangle_mesh_shape.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "deformable_sim/core/geometry/triangle_separation.h"

namespace deformable_sim::core {

namespace {

/// A point this near an edge or corner is on it, m: the way from the edge to it is rounding's and
/// says nothing of the surface's normal there (points held on a mesh are found inside by 1e-19 to
/// 1e-16 m).
constexpr double kRoundOff = 1e-12;

double signedVolume(const TriangleMesh& mesh) {
  double six_volume = 0.0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    six_volume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
  }
  return six_volume / 6.0;
}

// `mesh` once checked.
TriangleMesh checked(TriangleMesh mesh) {
  if (mesh.triangles.empty()) throw std::invalid_argument("the mesh has no triangle");
  for (const Eigen::Vector3d& v : mesh.vertices) {
    if (!v.allFinite()) throw std::invalid_argument("the mesh has a vertex that is not finite");
  }
  const int count = static_cast<int>(mesh.vertices.size());
  Eigen::Vector3d min = mesh.vertices.front(), max = min;
  for (const Eigen::Vector3d& v : mesh.vertices) {
    min = min.cwiseMin(v);
    max = max.cwiseMax(v);
  }
  const double tiny_area = 1e-14 * (max - min).squaredNorm();
  for (size_t k = 0; k < mesh.triangles.size(); ++k) {
    const Eigen::Vector3i& t = mesh.triangles[k];
    if ((t.array() < 0).any() || (t.array() >= count).any()) {
      throw std::invalid_argument("triangle " + std::to_string(k) +
                                  " has a vertex index out of range");
    }
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    if (!(0.5 * (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).norm() > tiny_area)) {
      throw std::invalid_argument("triangle " + std::to_string(k) + " has zero area");
    }
  }
  return mesh;
}

}  // namespace

TriangleMeshShape::TriangleMeshShape(TriangleMesh mesh, double open_depth)
    : mesh_(checked(std::move(mesh))), open_depth_(open_depth) {
  if (!(open_depth_ >= 0.0 && std::isfinite(open_depth_))) {
    throw std::invalid_argument("an open mesh's depth must be finite and >= 0 m");
  }
  findNeighbours();
  if (closed_ && signedVolume(mesh_) < 0.0) {
    for (Eigen::Vector3i& t : mesh_.triangles) std::swap(t[1], t[2]);  // it was inside out
    findNeighbours();
  }
  computePseudoNormals();
  findRidges();
  // Built over the mesh as it is kept, so that a shape made again from mesh() (a replay) has
  // the same tree and answers bit for bit the same.
  tree_ = TriangleAabbTree(mesh_);
  for (const Eigen::Vector3d& v : mesh_.vertices) bounds_.extend(v);
}

double TriangleMeshShape::dent(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c, const Eigen::Vector3d& inward,
                               double margin, std::vector<int>& near) const {
  const Eigen::Vector3d reach = Eigen::Vector3d::Constant(margin);
  near.clear();
  tree_.trianglesNear(a.cwiseMin(b).cwiseMin(c) - reach, a.cwiseMax(b).cwiseMax(c) + reach, near);
  double deepest = -std::numeric_limits<double>::infinity();
  for (int t : near) {
    const Eigen::Vector3i& corners = mesh_.triangles[t];
    deepest = std::max(deepest, dentDepth(a, b, c, inward, mesh_.vertices[corners[0]],
                                          mesh_.vertices[corners[1]], mesh_.vertices[corners[2]]));
  }
  return deepest;
}

// Pairs each directed edge with its reverse. Closed: every edge has one.
void TriangleMeshShape::findNeighbours() {
  std::map<std::pair<int, int>, std::pair<int, int>> edges;  // (from, to) -> (triangle, edge)
  for (size_t k = 0; k < mesh_.triangles.size(); ++k) {
    const Eigen::Vector3i& t = mesh_.triangles[k];
    for (int e = 0; e < 3; ++e) {
      if (!edges.emplace(std::make_pair(t[e], t[(e + 1) % 3]), std::make_pair(int(k), e)).second) {
        throw std::invalid_argument(
            "triangle " + std::to_string(k) +
            " runs along an edge in the same direction as another triangle: the triangles are "
            "not turned consistently, or more than two share an edge");
      }
    }
  }
  neighbours_.assign(mesh_.triangles.size(), {-1, -1, -1});
  closed_ = true;
  for (const auto& [edge, owner] : edges) {
    const auto reverse = edges.find({edge.second, edge.first});
    if (reverse == edges.end()) {
      closed_ = false;
    } else {
      neighbours_[owner.first][owner.second] = reverse->second.first;
    }
  }
}

void TriangleMeshShape::computePseudoNormals() {
  const size_t count = mesh_.triangles.size();
  face_normals_.resize(count);
  edge_normals_.resize(count);
  vertex_normals_.assign(mesh_.vertices.size(), Eigen::Vector3d::Zero());
  std::vector<bool> on_free_edge(mesh_.vertices.size(), false);
  for (size_t k = 0; k < count; ++k) {
    const Eigen::Vector3i& t = mesh_.triangles[k];
    const Eigen::Vector3d& a = mesh_.vertices[t[0]];
    face_normals_[k] = (mesh_.vertices[t[1]] - a).cross(mesh_.vertices[t[2]] - a).normalized();
  }
  for (size_t k = 0; k < count; ++k) {
    const Eigen::Vector3i& t = mesh_.triangles[k];
    for (int c = 0; c < 3; ++c) {
      const int across = neighbours_[k][c];
      edge_normals_[k][c] = across < 0 ? Eigen::Vector3d::Zero()
                                       : Eigen::Vector3d(face_normals_[k] + face_normals_[across]);
      if (across < 0) on_free_edge[t[c]] = on_free_edge[t[(c + 1) % 3]] = true;
      const Eigen::Vector3d& corner = mesh_.vertices[t[c]];
      const Eigen::Vector3d to_next = mesh_.vertices[t[(c + 1) % 3]] - corner;
      const Eigen::Vector3d to_previous = mesh_.vertices[t[(c + 2) % 3]] - corner;
      const double angle = std::atan2(to_next.cross(to_previous).norm(), to_next.dot(to_previous));
      vertex_normals_[t[c]] += angle * face_normals_[k];
    }
  }
  for (size_t v = 0; v < vertex_normals_.size(); ++v) {
    if (on_free_edge[v]) vertex_normals_[v].setZero();
  }
}

void TriangleMeshShape::findRidges() {
  ridges_.assign(mesh_.triangles.size(), {false, false, false});
  const double flat = std::cos(kRidgeAngle);
  for (size_t k = 0; k < mesh_.triangles.size(); ++k) {
    const Eigen::Vector3i& t = mesh_.triangles[k];
    for (int c = 0; c < 3; ++c) {
      const int across = neighbours_[k][c];
      if (across < 0) {
        ridges_[k][c] = true;
        continue;
      }
      if (across < static_cast<int>(k)) continue;  // spoken for by the other
      // Convex: the other triangle's far corner lies behind this one's plane.
      const Eigen::Vector3i& other = mesh_.triangles[across];
      int far = 0;
      while (other[far] == t[c] || other[far] == t[(c + 1) % 3]) ++far;
      const bool convex =
          face_normals_[k].dot(mesh_.vertices[other[far]] - mesh_.vertices[t[c]]) < 0.0;
      ridges_[k][c] = convex && face_normals_[k].dot(face_normals_[across]) < flat;
    }
  }
}

double TriangleMeshShape::signedDistance(const Eigen::Vector3d& p, Eigen::Vector3d* surface,
                                         Eigen::Vector3d* normal) const {
  const TriangleAabbTree::Nearest nearest = tree_.nearest(mesh_, p);
  const TriangleClosestPoint& closest = nearest.closest;
  const Eigen::Vector3d& face_normal = face_normals_[nearest.triangle];
  Eigen::Vector3d pseudo_normal = face_normal;
  Eigen::Vector3d point = closest.point;
  double distance = std::sqrt(nearest.squared_distance);
  if (closest.feature == TriangleClosestPoint::Feature::kFace) {
    // Along the face normal: exact for a point over a flat face, where the barycentric
    // combination would leave rounding in the tangential directions.
    const double height = face_normal.dot(p - mesh_.vertices[mesh_.triangles[nearest.triangle][0]]);
    point = p - height * face_normal;
    distance = std::abs(height);
  } else if (closest.feature == TriangleClosestPoint::Feature::kEdge) {
    pseudo_normal = edge_normals_[nearest.triangle][closest.index];
  } else {
    pseudo_normal = vertex_normals_[mesh_.triangles[nearest.triangle][closest.index]];
  }
  const Eigen::Vector3d offset = p - point;
  // A zero pseudo-normal marks a free edge or its corner: the space beyond is outside.
  const bool behind = offset.dot(pseudo_normal) < 0.0;
  const bool inside = behind && (closed_ || distance < open_depth_);
  if (surface) *surface = point;
  if (normal) {
    if (closest.feature == TriangleClosestPoint::Feature::kFace) {
      *normal = behind && !inside ? Eigen::Vector3d(-face_normal) : face_normal;
    } else if (distance > kRoundOff) {
      *normal = (inside ? -offset : offset) / distance;
    } else {  // on the edge or corner to round-off: the offset's way is noise
      *normal =
          pseudo_normal.isZero(0.0) ? face_normal : Eigen::Vector3d(pseudo_normal.normalized());
    }
  }
  return inside ? -distance : distance;
}

}  // namespace deformable_sim::core
