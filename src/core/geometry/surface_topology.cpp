#include "deformable_sim/core/geometry/surface_topology.h"

#include <algorithm>
#include <array>
#include <cstdint>

#include "deformable_sim/core/base/disjoint_sets.h"

namespace deformable_sim::core {

namespace {

// A triangle's side from one corner to the next; `forward` when it runs from the lower vertex
// index to the higher.
struct HalfEdge {
  uint64_t key;  ///< lower index << 32 | higher index
  int triangle;
  bool forward;
};

// Across an edge of two triangles: the other one, and whether it runs the edge the same way
// (then the two face opposite ways).
struct Link {
  int other = -1;
  bool same_way = false;
};

std::vector<HalfEdge> sortedHalfEdges(const TriangleMesh& surface) {
  std::vector<HalfEdge> half;
  half.reserve(3 * surface.triangles.size());
  for (int t = 0; t < static_cast<int>(surface.triangles.size()); ++t) {
    for (int c = 0; c < 3; ++c) {
      const uint32_t from = surface.triangles[t][c], to = surface.triangles[t][(c + 1) % 3];
      const uint64_t low = std::min(from, to), high = std::max(from, to);
      half.push_back({low << 32 | high, t, from < to});
    }
  }
  std::sort(half.begin(), half.end(), [](const HalfEdge& a, const HalfEdge& b) {
    return a.key != b.key ? a.key < b.key : a.triangle < b.triangle;
  });
  return half;
}

// Counts the open and overused edges, links the triangles across edges of two and joins every
// group of triangles sharing an edge in `shells`.
// `on_rim` marks the triangles with an edge that is not shared by exactly two.
void joinAcrossEdges(const std::vector<HalfEdge>& half, SurfaceTopology& topology,
                     std::vector<std::array<Link, 3>>& links, DisjointSets& shells,
                     std::vector<char>& on_rim) {
  for (size_t begin = 0, end = 0; begin < half.size(); begin = end) {
    end = begin + 1;
    while (end < half.size() && half[end].key == half[begin].key) ++end;
    const size_t users = end - begin;
    if (users == 1) ++topology.open_edges;
    if (users > 2) ++topology.overused_edges;
    for (size_t k = begin + 1; k < end; ++k) {
      shells.join(half[begin].triangle, half[k].triangle);
    }
    if (users != 2) {
      for (size_t k = begin; k < end; ++k) on_rim[half[k].triangle] = 1;
      continue;
    }
    const HalfEdge& a = half[begin];
    const HalfEdge& b = half[begin + 1];
    const bool same_way = a.forward == b.forward;
    for (Link& link : links[a.triangle]) {
      if (link.other < 0) {
        link = {b.triangle, same_way};
        break;
      }
    }
    for (Link& link : links[b.triangle]) {
      if (link.other < 0) {
        link = {a.triangle, same_way};
        break;
      }
    }
  }
}

// Walks each group of linked triangles from its first one, giving every triangle the way it
// faces relative to that one (a group that cannot face one way, like a Moebius strip, keeps what
// the walk met first), then marks the smaller part as facing against its neighbours.
void markAgainstNeighbours(const std::vector<std::array<Link, 3>>& links,
                           SurfaceTopology& topology) {
  const int n = static_cast<int>(links.size());
  std::vector<int> group(n, -1);
  std::vector<char> turned(n, 0);
  std::vector<std::array<int, 2>> counts;  // per group: triangles facing as the first, against
  std::vector<int> queue;
  for (int seed = 0; seed < n; ++seed) {
    if (group[seed] >= 0) continue;
    const int g = static_cast<int>(counts.size());
    counts.push_back({0, 0});
    group[seed] = g;
    queue.assign(1, seed);
    for (size_t q = 0; q < queue.size(); ++q) {
      const int t = queue[q];
      ++counts[g][turned[t]];
      for (const Link& link : links[t]) {
        if (link.other < 0 || group[link.other] >= 0) continue;
        group[link.other] = g;
        turned[link.other] = turned[t] ^ static_cast<char>(link.same_way);
        queue.push_back(link.other);
      }
    }
  }
  topology.against_neighbours.assign(n, 0);
  for (int t = 0; t < n; ++t) {
    const std::array<int, 2>& c = counts[group[t]];
    const char majority = c[1] > c[0] ? 1 : 0;
    topology.against_neighbours[t] = turned[t] != majority;
    topology.misoriented += topology.against_neighbours[t];
  }
}

}  // namespace

SurfaceTopology surfaceTopology(const TriangleMesh& surface) {
  const int n = static_cast<int>(surface.triangles.size());
  SurfaceTopology topology;
  std::vector<std::array<Link, 3>> links(n);
  DisjointSets shells(n);
  std::vector<char> on_rim(n, 0);
  joinAcrossEdges(sortedHalfEdges(surface), topology, links, shells, on_rim);
  markAgainstNeighbours(links, topology);
  std::vector<int> shell_of_root(n, -1);
  topology.shell_of.resize(n);
  for (int t = 0; t < n; ++t) {
    int& shell = shell_of_root[shells.root(t)];
    if (shell < 0) {
      shell = topology.shells++;
      topology.shell_closed.push_back(1);
    }
    topology.shell_of[t] = shell;
    if (on_rim[t]) topology.shell_closed[shell] = 0;
  }
  return topology;
}

}  // namespace deformable_sim::core
