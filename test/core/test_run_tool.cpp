// deformable_sim_run on the package's own scenes: what it says about robot links it cannot
// simulate offline, and the mean time per step and solves per step its summary gives, quiet or
// not.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <fstream>
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

// The mean of the summary line "<body>: M <what> per step (mean)", or -1.
double meanPerStep(const std::string& output, const std::string& body, const std::string& what) {
  const std::regex line(body + ": ([0-9.]+) " + what + R"( per step \(mean\))");
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

// A Neo-Hookean body's solves are its Newton iterations, and the summary says so; a warped one
// solves once a step unless its rotations within the step gain energy.
TEST(RunTool, SummaryGivesTheNewtonIterationsOfANeoHookeanBody) {
  const std::string scene = ::testing::TempDir() + "/neo_hookean_cantilever.yaml";
  std::ofstream(scene) << R"(dt: 0.01
effects: {gravity: [0.0, 0.0, -9.81]}
bodies:
  - name: beam
    mesh: {box: {min: [0.0, -0.05, -0.05], max: [0.5, 0.05, 0.05], cells: [8, 2, 2]}}
    material: {law: neo_hookean, youngs_modulus: 1.0e5, poisson_ratio: 0.3, density: 100.0}
    fixed: [{box: {min: [-1.0e-6, -1.0, -1.0], max: [1.0e-6, 1.0, 1.0]}}]
)";
  const Result run = deformable_sim::test::runCommand(std::string(DEFORMABLE_SIM_RUN) + " " +
                                                      scene + " --steps 30 --quiet 2>&1");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  // This soft beam drops by a tenth of its length in its first 0.3 s: 3.6 iterations a step, the
  // warped stiffness being further from the law's tangent than on the benchmark's stiffer
  // cantilever (1.5 there).
  const double newton = meanPerStep(run.output, "beam", "Newton iterations");
  EXPECT_GE(newton, 1.0) << run.output;
  EXPECT_LE(newton, 5.0) << run.output;
  const Result warped = runScene("cantilever.yaml", "--steps 3 --quiet");
  EXPECT_GE(meanPerStep(warped.output, "beam", "solves"), 1.0) << warped.output;
}
