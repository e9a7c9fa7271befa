// Union-find as mesh pieces and surface shells use it: which items a chain of joins put together.
#include <gtest/gtest.h>

#include "deformable_sim/core/base/disjoint_sets.h"

namespace dc = deformable_sim::core;

TEST(DisjointSets, EachItemStartsAsItsOwnSet) {
  dc::DisjointSets sets(4);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(sets.root(i), i);
}

TEST(DisjointSets, AChainOfJoinsPutsItsItemsInOneSetUnderTheRootOfTheKeptOne) {
  dc::DisjointSets sets(6);
  sets.join(0, 1);
  sets.join(1, 2);
  sets.join(4, 5);
  for (int i : {0, 1, 2}) EXPECT_EQ(sets.root(i), 0) << i;
  EXPECT_EQ(sets.root(3), 3);  // never joined
  EXPECT_EQ(sets.root(4), 4);
  EXPECT_EQ(sets.root(5), 4);
  // Joining two sets by any of their items keeps the root of the first's.
  sets.join(5, 2);
  for (int i : {0, 1, 2, 4, 5}) EXPECT_EQ(sets.root(i), 4) << i;
  EXPECT_EQ(sets.root(3), 3);
}

TEST(DisjointSets, JoiningItemsOfOneSetChangesNothing) {
  dc::DisjointSets sets(3);
  sets.join(0, 1);
  sets.join(1, 0);
  sets.join(1, 1);
  EXPECT_EQ(sets.root(0), 0);
  EXPECT_EQ(sets.root(1), 0);
  EXPECT_EQ(sets.root(2), 2);
}

TEST(DisjointSets, ALongChainEndsInOneSet) {
  // Each join hangs the next item under the last root: deep trees that path halving flattens.
  const int n = 10000;
  dc::DisjointSets sets(n);
  for (int i = 1; i < n; ++i) sets.join(i, i - 1);
  const int root = sets.root(0);
  EXPECT_EQ(root, n - 1);
  for (int i = 0; i < n; ++i) ASSERT_EQ(sets.root(i), root) << i;
}
