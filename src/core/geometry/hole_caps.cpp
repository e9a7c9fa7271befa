#include "deformable_sim/core/geometry/hole_caps.h"

#include <algorithm>
#include <map>
#include <utility>

#include "deformable_sim/core/base/disjoint_sets.h"

namespace deformable_sim::core {

namespace {

// Per edge (lower vertex, higher vertex): its uses from lower to higher less the others.
std::map<std::pair<int, int>, int> edgeBalance(const TriangleMesh& surface) {
  std::map<std::pair<int, int>, int> balance;
  for (const Eigen::Vector3i& t : surface.triangles) {
    for (int c = 0; c < 3; ++c) {
      const int u = t[c], v = t[(c + 1) % 3];
      if (u == v) continue;
      balance[{std::min(u, v), std::max(u, v)}] += u < v ? 1 : -1;
    }
  }
  return balance;
}

}  // namespace

bool isClosedSurface(const TriangleMesh& surface) {
  const std::map<std::pair<int, int>, int> balance = edgeBalance(surface);
  return std::all_of(balance.begin(), balance.end(), [](const auto& e) { return e.second == 0; });
}

TriangleMesh holeCaps(const TriangleMesh& surface) {
  std::vector<std::pair<std::pair<int, int>, int>> open;  // (from, to) and how often
  for (const auto& [edge, excess] : edgeBalance(surface)) {
    if (excess > 0) open.push_back({edge, excess});
    if (excess < 0) open.push_back({{edge.second, edge.first}, -excess});
  }
  // The holes: the open edges joined at their vertices.
  DisjointSets holes(static_cast<int>(surface.vertices.size()));
  for (const auto& [edge, count] : open) holes.join(edge.second, edge.first);
  TriangleMesh caps;
  caps.vertices = surface.vertices;
  std::map<int, int> apex_of;  // per hole (its root vertex): its apex
  std::map<int, std::pair<Eigen::Vector3d, int>> sums;
  for (const auto& [edge, count] : open) {
    auto& [sum, ends] =
        sums.try_emplace(holes.root(edge.first), Eigen::Vector3d::Zero(), 0).first->second;
    sum += surface.vertices[edge.first] + surface.vertices[edge.second];
    ends += 2;
  }
  for (const auto& [hole, sum] : sums) {
    apex_of[hole] = static_cast<int>(caps.vertices.size());
    caps.vertices.push_back(sum.first / sum.second);
  }
  // An edge used `count` times more from a to b: that many triangles b -> a -> apex cancel it;
  // their edges to the apex cancel around the hole, whose every vertex its edges enter as often
  // as they leave.
  for (const auto& [edge, count] : open) {
    for (int k = 0; k < count; ++k) {
      caps.triangles.emplace_back(edge.second, edge.first, apex_of[holes.root(edge.first)]);
    }
  }
  return caps;
}

}  // namespace deformable_sim::core
