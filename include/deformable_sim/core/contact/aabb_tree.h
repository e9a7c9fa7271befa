// A bounding-volume tree of axis-aligned boxes: the broad phase of contact between bodies. Built
// once over a surface's triangles, refitted in place when they move (the tree's shape stays, its
// boxes grow or shrink), so a step allocates nothing. A query visits every item whose box overlaps
// the given one.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <vector>

namespace deformable_sim::core {

using Box3 = Eigen::AlignedBox3d;

class AabbTree {
 public:
  /// The tree over boxes[0..n): items split at the median of the longest axis until a leaf holds
  /// at most kLeafSize of them. Allocates.
  void build(const std::vector<Box3>& boxes);
  /// The same items at new boxes (same count and order as given to build()). Allocates nothing.
  void refit(const std::vector<Box3>& boxes);

  /// Calls visit(item) for every item whose box overlaps `box`. Allocates nothing.
  template <class Visit>
  void query(const Box3& box, Visit&& visit) const {
    if (nodes_.empty()) return;
    std::array<int, kMaxDepth> stack;
    int size = 0;
    stack[size++] = 0;
    while (size > 0) {
      const Node& node = nodes_[stack[--size]];
      if (!node.box.intersects(box)) continue;
      if (node.left < 0) {
        for (int k = node.first; k < node.first + node.count; ++k) {
          if (boxes_[items_[k]].intersects(box)) visit(items_[k]);
        }
      } else {
        stack[size++] = node.left;
        stack[size++] = node.left + 1;
      }
    }
  }

  int numNodes() const { return static_cast<int>(nodes_.size()); }
  const Box3& rootBox() const { return nodes_.front().box; }

  static constexpr int kLeafSize = 4;

 private:
  /// A median split halves the items, so the depth is at most log2(n) + 1: far below this for
  /// any mesh that fits in memory; the query's stack holds one pending sibling per level.
  static constexpr int kMaxDepth = 128;

  struct Node {
    Box3 box;
    int left = -1;             ///< children at left and left + 1; -1 for a leaf
    int first = 0, count = 0;  ///< a leaf's items: items_[first, first + count)
  };
  /// Builds the subtree of items_[first, first + count) into nodes_[index].
  void split(const std::vector<Box3>& boxes, int index, int first, int count);

  std::vector<Node> nodes_;  ///< children after their parent, so refit() runs backwards
  std::vector<int> items_;   ///< item indices, grouped by leaf
  std::vector<Box3> boxes_;  ///< of each item, as last built or refitted
};

}  // namespace deformable_sim::core
