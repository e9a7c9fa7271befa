#include "deformable_sim/core/contact/aabb_tree.h"

#include <algorithm>

namespace deformable_sim::core {

void AabbTree::build(const std::vector<Box3>& boxes) {
  nodes_.clear();
  boxes_ = boxes;
  items_.resize(boxes.size());
  for (size_t k = 0; k < boxes.size(); ++k) items_[k] = static_cast<int>(k);
  if (boxes.empty()) return;
  nodes_.reserve(2 * boxes.size());
  nodes_.emplace_back();
  split(boxes, 0, 0, static_cast<int>(boxes.size()));
}

void AabbTree::split(const std::vector<Box3>& boxes, int index, int first, int count) {
  Box3 all, centres;
  for (int k = first; k < first + count; ++k) {
    all.extend(boxes[items_[k]]);
    centres.extend(boxes[items_[k]].center());
  }
  nodes_[index].box = all;
  nodes_[index].first = first;
  nodes_[index].count = count;
  if (count <= kLeafSize) return;
  int axis = 0;
  centres.sizes().maxCoeff(&axis);
  const int half = count / 2;
  std::nth_element(items_.begin() + first, items_.begin() + first + half,
                   items_.begin() + first + count,
                   [&](int a, int b) { return boxes[a].center()[axis] < boxes[b].center()[axis]; });
  const int left = static_cast<int>(nodes_.size());
  nodes_[index].left = left;
  nodes_.emplace_back();
  nodes_.emplace_back();
  split(boxes, left, first, half);
  split(boxes, left + 1, first + half, count - half);
}

void AabbTree::refit(const std::vector<Box3>& boxes) {
  std::copy(boxes.begin(), boxes.end(), boxes_.begin());
  for (int n = numNodes() - 1; n >= 0; --n) {
    Node& node = nodes_[n];
    if (node.left >= 0) {
      node.box = nodes_[node.left].box.merged(nodes_[node.left + 1].box);
      continue;
    }
    node.box.setEmpty();
    for (int k = node.first; k < node.first + node.count; ++k) node.box.extend(boxes[items_[k]]);
  }
}

}  // namespace deformable_sim::core
