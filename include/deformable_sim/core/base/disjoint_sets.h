// Disjoint sets of the items 0 .. n-1 (union-find with path halving): which items a chain of
// joins has put together, each set named by its root item.
#pragma once

#include <vector>

namespace deformable_sim::core {

class DisjointSets {
 public:
  /// n items, each a set of its own.
  explicit DisjointSets(int n);

  /// The root of the set that holds item i: the same for every item of a set.
  int root(int i);
  /// Puts the sets of `keep` and `other` together, under the root of `keep`'s.
  void join(int keep, int other);

 private:
  std::vector<int> parent_;
};

}  // namespace deformable_sim::core
