// The fit on a session of its own: a cantilever with a secret stiffness and damping, pushed at its
// tip and dragged by its clamp, measured by two tracked markers (1 mm noise) and a force/torque
// sensor at the clamp (0.02 N noise); E and stiffness damping fitted from a guess 2.5x off.
#include <gtest/gtest.h>
#include <ros/time.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>

#include "deformable_sim/ros/identification.h"
#include "lab_recording.h"

namespace deformable_sim::test {
namespace {

namespace fs = std::filesystem;

constexpr double kTrueE = 1.0e6, kTrueBeta = 0.01;

std::string beamScene(double youngs_modulus, double damping_stiffness) {
  return "dt: 0.01\n"
         "effects: {gravity: [0, 0, -9.81], warping: true, damping: {mass: 0.0, stiffness: " +
         std::to_string(damping_stiffness) +
         "}}\n"
         "solver: {method: direct}\n"
         "bodies:\n"
         "  - name: beam\n"
         "    mesh: {box: {min: [0, 0, 0], max: [0.3, 0.04, 0.04], cells: [10, 2, 2]}}\n"
         "    material: {youngs_modulus: " +
         std::to_string(youngs_modulus) +
         ", poisson_ratio: 0.3, density: 500.0}\n"
         "    fixed: [{box: {min: [-0.001, -1, -1], max: [0.001, 1, 1]}}]\n";
}

core::NodeTarget box(double x_min, double x_max) {
  core::NodeTarget target;
  target.box = core::Box{Eigen::Vector3d(x_min, -1, -1), Eigen::Vector3d(x_max, 1, 1)};
  return target;
}

// Pushed down at the tip, let go, then its clamp dragged up 2 cm over half a second.
LabRecording beamLab() {
  LabRecording lab;
  lab.scene_yaml = beamScene(kTrueE, kTrueBeta);
  lab.duration = 2.5;
  core::WrenchCommand push;
  push.source = "tip";
  push.body = "beam";
  push.nodes = box(0.299, 0.301);
  push.force = Eigen::Vector3d(0, 0.3, -1.0);
  lab.commands.emplace(20, push);
  lab.commands.emplace(70, core::ClearWrenchCommand{"tip"});
  for (long k = 130; k < 180; ++k) {
    core::FixCommand drag;
    drag.body = "beam";
    drag.nodes = box(-0.001, 0.001);
    drag.translation = Eigen::Vector3d(0, 0, 0.0004);
    lab.commands.emplace(k, drag);
  }
  lab.markers = {{"marker_tip", {0.3, 0.02, 0.02}}, {"marker_mid", {0.15, 0.02, 0.04}}};
  return lab;
}

struct FitFiles {
  fs::path directory;
  fs::path fit_file;
};

FitFiles writeBeamFit(const std::string& name) {
  FitFiles files{fs::temp_directory_path() / ("deformable_sim_identify_" + name), {}};
  fs::create_directories(files.directory);
  recordLab(beamLab(), (files.directory / "experiment.bag").string());
  std::ofstream(files.directory / "guess.yaml") << beamScene(2.5e6, 0.025);
  files.fit_file = files.directory / "fit.yaml";
  std::ofstream(files.fit_file)
      << "bag: experiment.bag\n"
         "scene: guess.yaml\n"
         "fit:\n"
         "  - {body: beam, parameter: youngs_modulus, min: 1.0e4, max: 1.0e8}\n"
         "  - {body: beam, parameter: damping_stiffness, min: 0.0, max: 0.05}\n"
         "observations:\n"
         "  - {tf: marker_tip, body: beam, at: [0.3, 0.02, 0.02], sigma: 0.001}\n"
         "  - {tf: marker_mid, body: beam, at: [0.15, 0.02, 0.04], sigma: 0.001}\n"
         "  - {wrench: /ft_sensor/wrench, reactions: beam, sigma: [0.02, 0.002]}\n"
         "out: fitted.yaml\n";
  return files;
}

TEST(FitBeam, FindsStiffnessAndDampingFromAGuessOff) {
  ros::Time::init();
  const FitFiles files = writeBeamFit("beam");
  ros_layer::IdentifyOptions options;
  options.fit_file = files.fit_file.string();
  options.threads = 2;
  char* text = nullptr;
  std::size_t size = 0;
  std::FILE* out = open_memstream(&text, &size);
  const ros_layer::IdentifyResult result = ros_layer::identify(options, out);
  std::fclose(out);
  const std::string printed(text, size);
  std::free(text);
  SCOPED_TRACE(printed);

  EXPECT_EQ(result.exit_code, 0);
  ASSERT_EQ(result.fit.values.size(), 2u);
  const double E = result.fit.values[0], beta = result.fit.values[1];
  EXPECT_NEAR(E, kTrueE, 0.03 * kTrueE);
  EXPECT_NEAR(beta, kTrueBeta, 0.2 * kTrueBeta);
  EXPECT_LE(std::abs(E - kTrueE), 3.0 * result.fit.standard_deviations[0]);
  EXPECT_LE(std::abs(beta - kTrueBeta), 3.0 * result.fit.standard_deviations[1]);
  // The markers' residual comes down to their noise.
  EXPECT_LT(result.after[0].first, 0.0015);
  EXPECT_GT(result.before[0].first, 2.0 * result.after[0].first);
  EXPECT_LT(result.after[2].first, 0.03);
  EXPECT_TRUE(std::regex_search(printed, std::regex("fitted beam youngs_modulus [0-9.e+]+ ± ")));
  EXPECT_TRUE(std::regex_search(printed, std::regex("iteration 1: cost ")));
  const YAML::Node fitted = YAML::LoadFile((files.directory / "fitted.yaml").string());
  EXPECT_DOUBLE_EQ(fitted["bodies"][0]["material"]["youngs_modulus"].as<double>(), E);
  EXPECT_NEAR(fitted["effects"]["damping"]["stiffness"].as<double>(), beta, 1e-9);
}

}  // namespace
}  // namespace deformable_sim::test
