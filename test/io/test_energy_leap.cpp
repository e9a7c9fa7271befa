// The watchdog's energy check on a blow-up that stays finite: two shipped tubes thrown end on
// (test/data/scenes/tubes_thrown_end_on.yaml). With nothing acting on them but each other, no
// step may leave either with more energy than the two had when thrown; without the check they
// reach 1e163 J within 100 steps (2e37 J in 6).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "deformable_sim/core/session/simulation.h"
#include "deformable_sim/io/scene_file.h"

namespace dc = deformable_sim::core;
namespace dio = deformable_sim::io;

TEST(EnergyLeap, TubesThrownEndOnNeverGainEnergy) {
  const std::string scene =
      std::string(DEFORMABLE_SIM_SOURCE_DIR) + "/test/data/scenes/tubes_thrown_end_on.yaml";
  dc::Simulation sim = dio::buildSimulation(dio::readSceneFile(scene), nullptr);
  double thrown = 0.0;  // J: kinetic, at rest shape
  for (const dc::Body& body : sim.bodies()) thrown += body.kineticEnergy() + body.elasticEnergy();
  ASSERT_GT(thrown, 0.05);  // two tubes of 52 g at 1 m/s
  std::vector<dc::StepReport> reports;
  double most = 0.0;
  long leaps = 0;
  for (int s = 0; s < 20; ++s) {
    sim.step(reports);
    double energy = 0.0;
    for (size_t b = 0; b < reports.size(); ++b) {
      const dc::Body& body = sim.bodies()[b];
      ASSERT_TRUE(body.stateIsFinite());
      energy += body.kineticEnergy() + body.elasticEnergy();
      leaps += reports[b].energy_leapt;
      if (reports[b].energy_leapt) EXPECT_TRUE(reports[b].recovered);
    }
    most = std::max(most, energy);
  }
  EXPECT_LE(most, thrown * (1.0 + 1e-9)) << "thrown with " << thrown << " J";  // round-off
  std::printf("most energy %.4g J of %.4g J thrown; %ld steps undone for a leap\n", most, thrown,
              leaps);
}
