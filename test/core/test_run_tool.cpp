// deformable_sim_run on the package's own scenes: what it says about robot links it cannot
// simulate offline, and the mean time per step its summary gives, quiet or not.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <regex>
#include <string>

#include "command_output.h"

namespace {

using Result = deformable_sim::test::CommandOutput;

Result runScene(const std::string& scene, const std::string& arguments) {
  const std::string command = std::string(DEFORMABLE_SIM_RUN) + " " + DEFORMABLE_SIM_SOURCE_DIR +
                              "/config/scenes/" + scene + " " + arguments + " 2>&1";
  return deformable_sim::test::runCommand(command);
}

// The mean ms per step of the summary line "N steps in T ms: M ms per step (mean)", or -1.
double meanStepMs(const std::string& output, long steps) {
  const std::regex line(std::to_string(steps) +
                        R"( steps in [0-9.]+ ms: ([0-9.]+) ms per step \(mean\))");
  std::smatch match;
  return std::regex_search(output, match, line) ? std::stod(match[1]) : -1.0;
}

const char* const kLinksNote =
    "urdf.links (table, left_finger, right_finger): robot links are not simulated offline; give "
    "them as obstacles";

}  // namespace

TEST(RunTool, SaysWhatItDoesWithRobotLinks) {
  const Result run = runScene("grasp_demo.yaml", "--steps 2 --quiet");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find(kLinksNote), std::string::npos) << run.output;
}

TEST(RunTool, SaysNothingOfRobotLinksWhenTheSceneHasNone) {
  const Result run = runScene("cantilever.yaml", "--steps 2 --quiet");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(run.output.find("urdf.links"), std::string::npos) << run.output;
}

TEST(RunTool, QuietSummaryGivesTheMeanTimePerStep) {
  const Result run = runScene("cantilever.yaml", "--steps 3 --quiet");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_GT(meanStepMs(run.output, 3), 0.0) << run.output;
  EXPECT_EQ(run.output.find("step 1 t="), std::string::npos) << "quiet, yet every step:\n"
                                                             << run.output;
  EXPECT_NE(run.output.find("after 3 steps beam: kinetic"), std::string::npos) << run.output;
}

TEST(RunTool, EveryStepAndTheMeanWhenNotQuiet) {
  const Result run = runScene("cantilever.yaml", "--steps 3");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("step 3 t="), std::string::npos) << run.output;
  EXPECT_GT(meanStepMs(run.output, 3), 0.0) << run.output;
}

// Offline, OpenMP's threads sleep between loops unless the user chose otherwise: spinning, they
// took the core a job beside them needed (doc/performance.md, "Beside another job").
TEST(RunTool, LetsItsOpenMpThreadsSleepUnlessToldOtherwise) {
  const auto policy = [](const std::string& environment) {
    const std::string command =
        "env " + environment + " " + DEFORMABLE_SIM_RUN + " " + DEFORMABLE_SIM_SOURCE_DIR +
        "/config/scenes/cantilever.yaml --steps 1000000 --quiet "
        ">/dev/null 2>&1 & p=$!; sleep 1; tr '\\0' '\\n' < /proc/$p/environ "
        "| grep '^OMP_WAIT_POLICY='; kill $p";
    return deformable_sim::test::runCommand(command).output;
  };
  EXPECT_EQ(policy("-u OMP_WAIT_POLICY"), "OMP_WAIT_POLICY=PASSIVE\n");
  EXPECT_EQ(policy("OMP_WAIT_POLICY=ACTIVE"), "OMP_WAIT_POLICY=ACTIVE\n");
}
