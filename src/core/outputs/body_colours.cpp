#include "deformable_sim/core/outputs/body_colours.h"

#include <array>

namespace deformable_sim::core {

namespace {

// Orange first (the colour every body had before there was a palette), then hues far from one
// another and from the grey of obstacles.
constexpr std::array<std::array<double, 3>, 6> kPalette = {{{1.0, 0.55, 0.1},
                                                            {0.2, 0.7, 0.9},
                                                            {0.75, 0.35, 0.85},
                                                            {0.2, 0.75, 0.55},
                                                            {0.95, 0.4, 0.6},
                                                            {0.6, 0.45, 0.25}}};

}  // namespace

Eigen::Vector3d paletteColour(int index) {
  const int n = static_cast<int>(kPalette.size());
  const std::array<double, 3>& c = kPalette[((index % n) + n) % n];
  return {c[0], c[1], c[2]};
}

std::vector<Eigen::Vector3d> bodyColours(const SceneSpec& scene) {
  std::vector<Eigen::Vector3d> colours;
  for (size_t b = 0; b < scene.bodies.size(); ++b) {
    const std::optional<Eigen::Vector3d>& own = scene.bodies[b].colour;
    colours.push_back(own ? *own : paletteColour(static_cast<int>(b)));
  }
  return colours;
}

}  // namespace deformable_sim::core
