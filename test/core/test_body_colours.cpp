#include <gtest/gtest.h>

#include "deformable_sim/core/outputs/body_colours.h"

namespace dc = deformable_sim::core;

TEST(BodyColours, EachBodyHasItsOwnOrThePalettesByIndex) {
  dc::SceneSpec scene;
  scene.bodies.resize(3);
  scene.bodies[2].colour = Eigen::Vector3d(0.1, 0.2, 0.3);
  const std::vector<Eigen::Vector3d> colours = dc::bodyColours(scene);
  ASSERT_EQ(colours.size(), 3u);
  EXPECT_EQ(colours[0], dc::paletteColour(0));
  EXPECT_EQ(colours[1], dc::paletteColour(1));
  EXPECT_GT((colours[0] - colours[1]).norm(), 0.3);  // told apart at a glance
  EXPECT_EQ(colours[2], Eigen::Vector3d(0.1, 0.2, 0.3));
}

TEST(BodyColours, ThePaletteRepeatsAndStaysInRange) {
  for (int b = 0; b < 20; ++b) {
    const Eigen::Vector3d c = dc::paletteColour(b);
    EXPECT_TRUE((c.array() >= 0.0).all() && (c.array() <= 1.0).all()) << b;
  }
  int period = 1;
  while (dc::paletteColour(period) != dc::paletteColour(0)) ++period;
  for (int b = 0; b < period; ++b) {
    EXPECT_EQ(dc::paletteColour(b + period), dc::paletteColour(b)) << b;
    for (int other = 0; other < b; ++other) {
      EXPECT_GT((dc::paletteColour(b) - dc::paletteColour(other)).norm(), 0.2) << b << other;
    }
  }
}
