// The self-crossing check's budget bounds the candidates it examines, not only the pairs it
// tests: a fan of many triangles about one vertex (a CAD cylinder's end) gives every triangle all
// the others as candidates, none of them a pair to test.
#include <gtest/gtest.h>

#include <cmath>

#include "deformable_sim/core/geometry/self_crossings.h"
#include "surface_test_helpers.h"

namespace dc = deformable_sim::core;
namespace dt = deformable_sim::test;

TEST(SelfCrossings, AFanAboutOneVertexStopsWithinItsBudgetOfCandidates) {
  constexpr int kTriangles = 20000;
  dc::TriangleMesh fan;
  fan.vertices.emplace_back(0.0, 0.0, 0.0);
  for (int s = 0; s < kTriangles; ++s) {
    const double azimuth = 2.0 * M_PI * s / kTriangles;
    fan.vertices.emplace_back(std::cos(azimuth), std::sin(azimuth), 0.0);
  }
  for (int s = 0; s < kTriangles; ++s)
    fan.triangles.emplace_back(0, 1 + s, 1 + (s + 1) % kTriangles);
  const dc::SelfCrossings found = dc::selfCrossings(fan);
  EXPECT_LE(found.candidates, 256L * kTriangles);  // not the 4e8 of every pair
  EXPECT_FALSE(found.complete);
  EXPECT_EQ(found.pairs, 0);
}

TEST(SelfCrossings, ACylinderWithEndsOfAHundredTrianglesIsCheckedWhole) {
  const dc::TriangleMesh rod = dt::cylinderSurface(0.02, 0.3, 128);
  const dc::SelfCrossings found = dc::selfCrossings(rod);
  EXPECT_TRUE(found.complete);
  EXPECT_EQ(found.pairs, 0);
  EXPECT_GT(found.candidates, static_cast<long>(rod.triangles.size()));
}
