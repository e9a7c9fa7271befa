// Two more fits on sessions of their own: Poisson's ratio with E from a block squeezed by a load
// on its top (nu shows in its bulge), and friction from a block sliding down a slope.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "deformable_sim/io/scene_file.h"
#include "fit_run.h"
#include "lab_recording.h"

namespace deformable_sim::test {
namespace {

namespace fs = std::filesystem;

fs::path recorded(const std::string& name, const LabRecording& lab, const std::string& guess) {
  const fs::path directory = fs::temp_directory_path() / ("deformable_sim_identify_" + name);
  fs::create_directories(directory);
  recordLab(lab, (directory / "experiment.bag").string());
  std::ofstream(directory / "guess.yaml") << guess;
  return directory;
}

// A 10 cm foam cube on its fixed base, loaded on its top in steps up to 40 N; of `law`.
std::string squeezedScene(double youngs_modulus, double poisson_ratio,
                          const std::string& law = "corotational") {
  return "dt: 0.01\n"
         "effects: {warping: true, damping: {mass: 0.0, stiffness: 0.005}}\n"
         "solver: {method: direct}\n"
         "bodies:\n"
         "  - name: block\n"
         "    mesh: {box: {min: [0, 0, 0], max: [0.1, 0.1, 0.1], cells: [4, 4, 4]}}\n"
         "    material: {law: " +
         law + ", youngs_modulus: " + std::to_string(youngs_modulus) +
         ", poisson_ratio: " + std::to_string(poisson_ratio) +
         ", density: 200.0}\n"
         "    fixed: [{box: {min: [-1, -1, -0.001], max: [1, 1, 0.001]}}]\n"
         "    groups: {top: {box: {min: [-1, -1, 0.099], max: [1, 1, 0.101]}}}\n";
}

// A recording of the block in `scene` for `duration` s.
LabRecording blockLab(const std::string& scene, double duration) {
  LabRecording lab;
  lab.scene_yaml = scene;
  lab.body = "block";
  lab.duration = duration;
  return lab;
}

// The fit of E and nu from 2x off and 0.15, with these observations.
std::string squeezeFit(const std::string& observations) {
  return "bag: experiment.bag\n"
         "scene: guess.yaml\n"
         "fit:\n"
         "  - {body: block, parameter: youngs_modulus, min: 1.0e3, max: 1.0e7}\n"
         "  - {body: block, parameter: poisson_ratio, min: 0.0, max: 0.49}\n"
         "observations:\n" +
         observations + "out: fitted.yaml\n";
}

// The cube of `law` pressed in four steps up to 40 N (8 % of its height at E = 50 kPa), recorded
// by three markers and the sensor under its base; E and nu fitted from 2x off and 0.15.
FitRun fitTheBulge(const std::string& law) {
  LabRecording lab = blockLab(squeezedScene(5.0e4, 0.35, law), 1.2);
  for (int load = 1; load <= 4; ++load) {
    core::WrenchCommand press;
    press.source = "press";
    press.body = "block";
    press.nodes.group = "top";
    press.force = Eigen::Vector3d(0, 0, -10.0 * load);
    lab.commands.emplace(20 * load, press);
  }
  lab.markers = {
      {"top", {0.05, 0.05, 0.1}}, {"side_x", {0.1, 0.05, 0.05}}, {"side_y", {0.05, 0.1, 0.05}}};
  const fs::path directory = recorded("block_" + law, lab, squeezedScene(1.0e5, 0.15, law));
  return runFit(
      directory,
      squeezeFit("  - {tf: top, body: block, at: [0.05, 0.05, 0.1], sigma: 0.001}\n"
                 "  - {tf: side_x, body: block, at: [0.1, 0.05, 0.05], sigma: 0.001}\n"
                 "  - {tf: side_y, body: block, at: [0.05, 0.1, 0.05], sigma: 0.001}\n"
                 "  - {wrench: /ft_sensor/wrench, reactions: block, sigma: [0.02, 0.002]}\n"));
}

TEST(FitBlock, FindsPoissonsRatioAndStiffnessFromTheBulge) {
  expectFitted(fitTheBulge("corotational"), {5.0e4, 0.35}, {0.03, 0.05});
}

// The same of a Neo-Hookean cube: the fit steps the law it was given, and writes it back.
TEST(FitBlock, FindsANeoHookeanCubesStiffnessAndPoissonsRatio) {
  const FitRun run = fitTheBulge("neo_hookean");
  expectFitted(run, {5.0e4, 0.35}, {0.03, 0.05});
  const std::string fitted =
      (fs::temp_directory_path() / "deformable_sim_identify_block_neo_hookean" / "fitted.yaml")
          .string();
  EXPECT_EQ(io::readSceneFile(fitted).bodies.at(0).material.law, core::ElasticLaw::kNeoHookean);
}

// The same cube squeezed 9 mm by a gripper holding its top, the gripper's sensor and the two
// side markers measuring: E and nu from the grasp's wrench.
TEST(FitBlock, FindsStiffnessFromAGripsWrench) {
  LabRecording lab = blockLab(squeezedScene(5.0e4, 0.35), 1.0);
  lab.sensor_topic = "/gripper/wrench";
  lab.sensor_grasp = "gripper";
  core::GraspCommand grasp;
  grasp.name = "gripper";
  grasp.body = "block";
  grasp.nodes.group = "top";
  grasp.frame.translation() = Eigen::Vector3d(0.05, 0.05, 0.1);
  lab.commands.emplace(10, grasp);
  for (long k = 1; k <= 30; ++k) {
    core::MoveGraspCommand move{"gripper", grasp.frame};
    move.frame.translation().z() -= 0.0003 * static_cast<double>(k);
    lab.commands.emplace(10 + k, move);
  }
  lab.markers = {{"side_x", {0.1, 0.05, 0.05}}, {"side_y", {0.05, 0.1, 0.05}}};
  const fs::path directory = recorded("grasp", lab, squeezedScene(1.0e5, 0.15));
  const FitRun run =
      runFit(directory,
             squeezeFit("  - {tf: side_x, body: block, at: [0.1, 0.05, 0.05], sigma: 0.001}\n"
                        "  - {tf: side_y, body: block, at: [0.05, 0.1, 0.05], sigma: 0.001}\n"
                        "  - {wrench: /gripper/wrench, grasp: gripper, sigma: [0.02, 0.002]}\n"));
  expectFitted(run, {5.0e4, 0.35}, {0.03, 0.05});
  // A grasp the session never had would be compared with zero: refused.
  const std::string refusal =
      runFit(directory,
             squeezeFit("  - {wrench: /gripper/wrench, grasp: hand, sigma: [0.02, 0.002]}\n"))
          .refusal;
  EXPECT_NE(refusal.find("observations[0].grasp: the bag's log has no grasp 'hand' (its grasps: "
                         "gripper)"),
            std::string::npos)
      << refusal;
}

// A 10 cm block on a floor with gravity tilted by 30 degrees: a slope it slides down whenever
// friction is below tan 30 = 0.577, given a nudge at the start. A marker on it, and the floor's
// contact wrench (`link:`) as a force plate under it would read it.
std::string slopeScene(double friction) {
  return "dt: 0.01\n"
         "effects: {gravity: [0, -4.905, -8.49571], warping: true,\n"
         "          damping: {mass: 0.0, stiffness: 0.01}, contact: {friction: " +
         std::to_string(friction) +
         "}}\n"
         "solver: {method: direct}\n"
         "obstacles:\n"
         "  - {name: floor, box: {size: [4, 4, 0.2]}, position: [0, 0, -0.1]}\n"
         "bodies:\n"
         "  - name: block\n"
         "    mesh: {box: {min: [-0.05, -0.05, 0], max: [0.05, 0.05, 0.1], cells: [2, 2, 2]}}\n"
         "    material: {youngs_modulus: 1.0e5, poisson_ratio: 0.3, density: 500.0}\n";
}

// A 1 N push down the slope for the first 5 steps; a marker on the block's top.
void nudgeDownTheSlope(LabRecording& lab) {
  core::WrenchCommand nudge;
  nudge.source = "nudge";
  nudge.body = "block";
  nudge.nodes.whole_body = true;
  nudge.force = Eigen::Vector3d(0, -1.0, 0);
  lab.commands.emplace(0, nudge);
  lab.commands.emplace(5, core::ClearWrenchCommand{"nudge"});
  lab.markers = {{"top", {0.0, 0.0, 0.1}}};
}

TEST(FitBlock, FindsFrictionFromASlide) {
  LabRecording lab = blockLab(slopeScene(0.3), 1.0);
  lab.sensor_topic = "/floor/wrench";
  lab.sensor_link = "floor";
  nudgeDownTheSlope(lab);
  const fs::path directory = recorded("slope", lab, slopeScene(0.12));
  const FitRun run = runFit(directory,
                            "bag: experiment.bag\n"
                            "scene: guess.yaml\n"
                            "fit: [{body: block, parameter: friction, min: 0.01, max: 1.0}]\n"
                            "observations:\n"
                            "  - {tf: top, body: block, at: [0, 0, 0.1], sigma: 0.001}\n"
                            "  - {wrench: /floor/wrench, link: floor, sigma: [0.02, 0.002]}\n"
                            "out: fitted.yaml\n");
  expectFitted(run, {0.3}, {0.03});
  // A link the session never had would be compared with zero: refused.
  const std::string refusal =
      runFit(directory,
             "bag: experiment.bag\nscene: guess.yaml\n"
             "fit: [{body: block, parameter: friction, min: 0.01, max: 1.0}]\n"
             "observations: [{wrench: /floor/wrench, link: table, sigma: [0.02, 0.002]}]\n"
             "out: fitted.yaml\n")
          .refusal;
  EXPECT_NE(refusal.find("observations[0].link: neither the scene nor the bag's log has an "
                         "obstacle 'table' (they have: floor)"),
            std::string::npos)
      << refusal;
}

// Without `scene:` the fit starts from the bag's ~scene: the scene the node ran with, its
// friction the nominal 0.12, and writes `out` from that scene's text.
// The slide (friction 0.3) recorded for `duration` s by a node whose ~scene says 0.12, with a
// marker and no sensor, into a folder `name`.
fs::path slideWithNodeScene(const std::string& name, double duration) {
  LabRecording lab = blockLab(slopeScene(0.3), duration);
  lab.node_scene_yaml = slopeScene(0.12);
  lab.sensor_topic.clear();
  nudgeDownTheSlope(lab);
  return recorded(name, lab, "");
}

TEST(FitBlock, StartsFromTheRecordedSceneWithoutASceneFile) {
  const fs::path directory = slideWithNodeScene("recorded_scene", 1.0);
  const FitRun run =
      runFit(directory,
             "bag: experiment.bag\n"
             "fit: [{body: block, parameter: friction, min: 0.01, max: 1.0}]\n"
             "observations: [{tf: top, body: block, at: [0, 0, 0.1], sigma: 0.001}]\n"
             "out: fitted.yaml\n");
  expectFitted(run, {0.3}, {0.03});
  EXPECT_NE(run.printed.find("iteration 0: cost 7"), std::string::npos);  // from 0.12
  const core::SceneSpec fitted = io::readSceneFile((directory / "fitted.yaml").string());
  ASSERT_TRUE(fitted.contact);
  EXPECT_DOUBLE_EQ(fitted.contact->friction, run.result.fit.values[0]);
}

// A scene file that is not the bag's would re-simulate another session: refused, naming what
// differs (a command for body `beam` against a scene with only `bar` was dropped silently, and
// the fit ended with an RMS 176 times the noise).
TEST(FitBlock, RefusesASceneThatIsNotTheBags) {
  const fs::path directory = slideWithNodeScene("other_scene", 0.3);
  const auto fit = [](const std::string& body) {
    return "bag: experiment.bag\nscene: guess.yaml\nfit: [{body: " + body +
           ", parameter: friction, min: 0.01, max: 1.0}]\nobservations: [{tf: top, body: " + body +
           ", at: [0, 0, 0.1], sigma: 0.001}]\nout: fitted.yaml\n";
  };
  // What follows the fit file's name and the "scene: " key.
  const auto refusal = [&](const std::string& scene, const std::string& body = "block") {
    std::ofstream(directory / "guess.yaml") << scene;
    const std::string message = runFit(directory, fit(body)).refusal;
    return message.substr(std::min(message.size(), message.find(": ") + 2));
  };
  EXPECT_EQ(refusal(replaced(slopeScene(0.12), "name: block", "name: bar"), "bar"),
            "scene: the bag's log commands body 'block' (episode 0, step 0), which the scene does "
            "not have (it has bar): the scene is not the bag's");
  EXPECT_EQ(refusal(replaced(slopeScene(0.12), "dt: 0.01", "dt: 0.005")),
            "scene: its dt is 0.005000 s, the bag's node stepped 0.010000 s: the scene is not the "
            "bag's");
  EXPECT_EQ(refusal(replaced(slopeScene(0.12), "cells: [2, 2, 2]", "cells: [3, 3, 3]")),
            "scene: body 'block' has 64 nodes, the bag's 27: the scene is not the bag's");
  // The bag's own scene, from a file: fitted.
  EXPECT_EQ(refusal(slopeScene(0.12)), "");
}

}  // namespace
}  // namespace deformable_sim::test
