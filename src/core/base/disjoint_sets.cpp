#include "deformable_sim/core/base/disjoint_sets.h"

#include <numeric>

namespace deformable_sim::core {

DisjointSets::DisjointSets(int n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }

int DisjointSets::root(int i) {
  while (parent_[i] != i) {
    parent_[i] = parent_[parent_[i]];
    i = parent_[i];
  }
  return i;
}

void DisjointSets::join(int keep, int other) { parent_[root(other)] = root(keep); }

}  // namespace deformable_sim::core
