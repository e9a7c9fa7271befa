#include "deformable_sim/core/surface_bodies/surface_check.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>

#include "deformable_sim/core/geometry/hole_caps.h"
#include "deformable_sim/core/geometry/surface_topology.h"
#include "deformable_sim/core/geometry/winding_number.h"
#include "deformable_sim/core/surface_bodies/voxelization.h"

namespace deformable_sim::core {

namespace {

void turn(Eigen::Vector3i& triangle) { std::swap(triangle[1], triangle[2]); }

// Twice the triangle's area times its unit normal.
Eigen::Vector3d areaNormal(const TriangleMesh& surface, const Eigen::Vector3i& t) {
  const Eigen::Vector3d& a = surface.vertices[t[0]];
  return (surface.vertices[t[1]] - a).cross(surface.vertices[t[2]] - a);
}

// Keeps the triangles `keep` marks, in order; returns how many went.
int keepOnly(TriangleMesh& surface, const std::vector<char>& keep) {
  size_t kept = 0;
  for (size_t t = 0; t < surface.triangles.size(); ++t) {
    if (keep[t]) surface.triangles[kept++] = surface.triangles[t];
  }
  const int dropped = static_cast<int>(surface.triangles.size() - kept);
  surface.triangles.resize(kept);
  return dropped;
}

// Drops the triangles with an area below 1e-14 of the squared diagonal of the surface's box (as
// core::TriangleMeshShape refuses them): their corners coincide or lie on a line.
int dropZeroArea(TriangleMesh& surface) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3i& t : surface.triangles) {
    for (int c = 0; c < 3; ++c) box.extend(surface.vertices[t[c]]);
  }
  const double tiny = box.isEmpty() ? 0.0 : 1e-14 * box.sizes().squaredNorm();
  std::vector<char> keep(surface.triangles.size());
  for (size_t t = 0; t < keep.size(); ++t) {
    keep[t] = 0.5 * areaNormal(surface, surface.triangles[t]).norm() > tiny;
  }
  return keepOnly(surface, keep);
}

// A triangle's corners from the lowest index on, and whether they then rise (a triangle and its
// turned copy have the same corners and differ in this).
std::pair<std::array<int, 3>, bool> cornersOf(const Eigen::Vector3i& t) {
  int first = 0;
  if (t[1] < t[first]) first = 1;
  if (t[2] < t[first]) first = 2;
  const int b = t[(first + 1) % 3], c = t[(first + 2) % 3];
  return {{t[first], std::min(b, c), std::max(b, c)}, b < c};
}

// Of each group of triangles with the same corners, keeps one facing the way most of them face,
// or none when as many face each way (their solid angles cancel in the winding number).
int dropDuplicates(TriangleMesh& surface) {
  const int n = static_cast<int>(surface.triangles.size());
  std::vector<int> order(n);
  for (int t = 0; t < n; ++t) order[t] = t;
  std::vector<std::pair<std::array<int, 3>, bool>> corners(n);
  for (int t = 0; t < n; ++t) corners[t] = cornersOf(surface.triangles[t]);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return corners[a].first != corners[b].first ? corners[a].first < corners[b].first : a < b;
  });
  std::vector<char> keep(n, 0);
  for (int begin = 0, end = 0; begin < n; begin = end) {
    int rising = 0;
    for (end = begin; end < n && corners[order[end]].first == corners[order[begin]].first; ++end) {
      rising += corners[order[end]].second ? 1 : -1;
    }
    if (rising == 0) continue;
    for (int k = begin; k < end; ++k) {
      if (corners[order[k]].second == (rising > 0)) {
        keep[order[k]] = 1;
        break;
      }
    }
  }
  return keepOnly(surface, keep);
}

// Drops the vertices no triangle uses, keeping the order of the others.
void dropUnusedVertices(TriangleMesh& surface) {
  std::vector<int> index(surface.vertices.size(), -1);
  for (const Eigen::Vector3i& t : surface.triangles) {
    for (int c = 0; c < 3; ++c) index[t[c]] = 0;
  }
  int used = 0;
  for (size_t v = 0; v < index.size(); ++v) {
    if (index[v] < 0) continue;
    index[v] = used;
    surface.vertices[used++] = surface.vertices[v];  // used <= v: nothing unread is overwritten
  }
  surface.vertices.resize(used);
  for (Eigen::Vector3i& t : surface.triangles) {
    for (int c = 0; c < 3; ++c) t[c] = index[t[c]];
  }
}

struct Shell {
  double volume = 0.0;  ///< signed, about the surface's first vertex, m^3
  int largest = -1;     ///< its triangle of the largest area
  double largest_area = 0.0;
};

std::vector<Shell> shellsOf(const TriangleMesh& surface, const SurfaceTopology& topology) {
  std::vector<Shell> shells(topology.shells);
  const Eigen::Vector3d& o = surface.vertices.front();
  for (int t = 0; t < static_cast<int>(surface.triangles.size()); ++t) {
    const Eigen::Vector3i& v = surface.triangles[t];
    Shell& shell = shells[topology.shell_of[t]];
    shell.volume += (surface.vertices[v[0]] - o)
                        .dot((surface.vertices[v[1]] - o).cross(surface.vertices[v[2]] - o)) /
                    6.0;
    const double area = 0.5 * areaNormal(surface, v).norm();
    if (area > shell.largest_area) {
      shell.largest = t;
      shell.largest_area = area;
    }
  }
  return shells;
}

// Turns the closed shells that face inwards and lie inside no other shell: at a point just
// behind the shell's largest triangle (outside the shell), the winding number is that of the
// other shells alone, about 1 inside one of them (then the shell is a void) and 0 outside all.
void turnLoneInwardShells(TriangleMesh& surface, const SurfaceTopology& topology,
                          SurfaceCheck& check) {
  const std::vector<Shell> shells = shellsOf(surface, topology);
  std::vector<size_t> inward;
  for (size_t s = 0; s < shells.size(); ++s) {
    if (topology.shell_closed[s] && shells[s].volume < 0.0 && shells[s].largest >= 0) {
      inward.push_back(s);
    }
  }
  if (inward.empty()) return;
  std::vector<char> turn_shell(shells.size(), 0);
  const WindingNumber winding(surface);
  for (size_t s : inward) {
    const Eigen::Vector3i& t = surface.triangles[shells[s].largest];
    const Eigen::Vector3d centre =
        (surface.vertices[t[0]] + surface.vertices[t[1]] + surface.vertices[t[2]]) / 3.0;
    const Eigen::Vector3d normal = areaNormal(surface, t).normalized();
    const double offset = 1e-3 * std::sqrt(shells[s].largest_area);
    if (winding.at(centre - offset * normal) >= 0.5) {
      ++check.voids;
    } else {
      turn_shell[s] = 1;
      ++check.turned_shells;
    }
  }
  for (size_t t = 0; t < surface.triangles.size(); ++t) {
    if (turn_shell[topology.shell_of[t]]) turn(surface.triangles[t]);
  }
}

// Turns the triangles that face against their neighbours, then the whole surface if it encloses
// a negative volume, then the lone shells that still face inwards.
void orient(TriangleMesh& surface, const SurfaceTopology& topology, SurfaceCheck& check) {
  for (size_t t = 0; t < surface.triangles.size(); ++t) {
    if (topology.against_neighbours[t]) turn(surface.triangles[t]);
  }
  // With its holes capped the surface is closed, and its volume does not depend on the point
  // it is taken about (an open one's does: a cup open at the bottom, taken about its top, can
  // come out negative).
  if (enclosedVolume(surface) + enclosedVolume(holeCaps(surface)) < 0.0) {
    check.inside_out = true;
    for (Eigen::Vector3i& t : surface.triangles) turn(t);
  }
  if (topology.shells > 1) turnLoneInwardShells(surface, topology, check);
}

}  // namespace

SurfaceCheck checkSurface(TriangleMesh& surface, int zero_area_dropped) {
  SurfaceCheck check;
  check.zero_area = zero_area_dropped + dropZeroArea(surface);
  check.duplicates = dropDuplicates(surface);
  dropUnusedVertices(surface);
  if (surface.triangles.empty()) return check;
  const SurfaceTopology topology = surfaceTopology(surface);
  check.open_edges = topology.open_edges;
  check.overused_edges = topology.overused_edges;
  check.misoriented = topology.misoriented;
  check.shells = topology.shells;
  orient(surface, topology, check);
  check.crossings = selfCrossings(surface);
  return check;
}

namespace {

// "1 triangle", "3 triangles".
std::string counted(int count, const std::string& noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

// The parts that are not empty, joined by ", ".
std::string listOf(const std::vector<std::string>& parts) {
  std::string list;
  for (const std::string& part : parts) {
    if (!part.empty()) list += (list.empty() ? "" : ", ") + part;
  }
  return list;
}

const char kByWindingNumber[] = "inside is judged by the winding number, volume may be off";

std::string droppedWarning(const SurfaceCheck& check) {
  if (check.zero_area + check.duplicates == 0) return "";
  return counted(check.zero_area + check.duplicates, "triangle") + " dropped: " +
         listOf({check.zero_area > 0 ? std::to_string(check.zero_area) + " with zero area" : "",
                 check.duplicates > 0 ? counted(check.duplicates, "duplicate") : ""});
}

// Only when a shell faced inwards: separate shells that face outwards are the separate pieces
// the voxelizer reports, or overlap (and then their triangles cross).
std::string shellsWarning(const SurfaceCheck& check) {
  if (check.voids + check.turned_shells == 0) return "";
  const std::string kinds =
      listOf({check.voids > 0 ? counted(check.voids, "void") + " inside another shell" : "",
              check.turned_shells > 0
                  ? std::to_string(check.turned_shells) + " facing inwards alone, turned outwards"
                  : ""});
  return counted(check.shells, "shell") + " (separate surfaces" +
         (kinds.empty() ? "" : ": " + kinds) + ")";
}

std::string crossingsWarning(const SelfCrossings& crossings) {
  if (crossings.pairs == 0) return "";
  return std::string(crossings.complete ? "" : "at least ") + counted(crossings.pairs, "pair") +
         " of triangles cross (the surface passes through itself; inside is judged by the "
         "winding number, so parts that overlap count once)";
}

}  // namespace

std::vector<std::string> surfaceWarnings(const SurfaceCheck& check) {
  std::vector<std::string> warnings{droppedWarning(check)};
  if (check.open_edges > 0) {
    warnings.push_back(counted(check.open_edges, "open edge") + " (the surface has holes; " +
                       kByWindingNumber + ")");
  }
  if (check.overused_edges > 0) {
    warnings.push_back(counted(check.overused_edges, "edge") +
                       " shared by more than two triangles (" + kByWindingNumber + ")");
  }
  if (check.misoriented > 0) {
    warnings.push_back(counted(check.misoriented, "triangle") +
                       " faced against their neighbours and turned to agree with them");
  }
  if (check.inside_out) {
    warnings.push_back(
        "the surface faced inwards (it enclosed a negative volume) and was turned outwards");
  }
  warnings.push_back(shellsWarning(check));
  warnings.push_back(crossingsWarning(check.crossings));
  warnings.erase(std::remove(warnings.begin(), warnings.end(), std::string()), warnings.end());
  return warnings;
}

}  // namespace deformable_sim::core
