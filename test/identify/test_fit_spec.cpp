// The fit file's reader: what it reads, and every refusal naming its key.
#include <gtest/gtest.h>

#include <string>

#include "deformable_sim/identify/fit_spec.h"
#include "deformable_sim/identify/fitted_scene.h"
#include "deformable_sim/identify/material_point.h"
#include "deformable_sim/identify/observed_series.h"
#include "deformable_sim/identify/scene_parameter.h"
#include "deformable_sim/io/scene_file.h"

namespace deformable_sim::identify {
namespace {

const std::string kFit =
    "bag: experiment.bag\n"
    "scene: scene.yaml\n"
    "fit:\n"
    "  - {body: beam, parameter: youngs_modulus, min: 1.0e4, max: 1.0e7}\n"
    "  - {body: beam, parameter: damping_stiffness, min: 0.0, max: 0.05}\n"
    "observations:\n"
    "  - {tf: marker_tip, body: beam, at: [0.3, 0.03, 0.02], sigma: 0.001}\n"
    "  - {wrench: /ft_sensor/wrench, reactions: beam, sigma: [0.02, 0.002]}\n"
    "out: fitted.yaml\n";

// The message parseFitSpec throws for `text`, or "" when it reads it.
std::string refusal(const std::string& text) {
  try {
    parseFitSpec(text, "fit.yaml", "/data");
  } catch (const FitSpecError& e) {
    return e.what();
  }
  return "";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(FitSpec, ReadsTheIssuesExample) {
  const FitSpec spec = parseFitSpec(kFit, "fit.yaml", "/data");
  EXPECT_EQ(spec.bag, "/data/experiment.bag");
  EXPECT_EQ(spec.scene, "/data/scene.yaml");
  EXPECT_EQ(spec.out, "/data/fitted.yaml");
  ASSERT_EQ(spec.fit.size(), 2u);
  EXPECT_EQ(spec.fit[1].parameter, "damping_stiffness");
  EXPECT_EQ(spec.fit[1].max, 0.05);
  ASSERT_EQ(spec.observations.size(), 2u);
  EXPECT_EQ(spec.observations[0].kind, ObservationSpec::Kind::kFrame);
  EXPECT_EQ(spec.observations[0].at, Eigen::Vector3d(0.3, 0.03, 0.02));
  EXPECT_EQ(spec.observations[1].kind, ObservationSpec::Kind::kWrench);
  EXPECT_EQ(spec.observations[1].source, ObservationSpec::Source::kReactions);
  EXPECT_EQ(spec.observations[1].body, "beam");
  EXPECT_EQ(spec.observations[1].torque_sigma, 0.002);
}

TEST(FitSpec, SceneIsOptionalAndGraspsAndLinksAreSources) {
  std::string text = replaced(kFit, "scene: scene.yaml\n", "");
  text = replaced(text, "reactions: beam", "grasp: left");
  const FitSpec spec = parseFitSpec(text, "fit.yaml", "/data");
  EXPECT_TRUE(spec.scene.empty());
  EXPECT_EQ(spec.observations[1].source, ObservationSpec::Source::kGrasp);
  EXPECT_EQ(spec.observations[1].name, "left");
}

TEST(FitSpec, RefusesNamingTheKey) {
  EXPECT_EQ(refusal(replaced(kFit, "bag: experiment.bag\n", "")), "fit.yaml:1: bag: missing");
  EXPECT_EQ(refusal(replaced(kFit, "out: fitted.yaml\n", "")), "fit.yaml:1: out: missing");
  EXPECT_EQ(refusal(kFit + "outt: x\n"), "fit.yaml:10: outt: unknown key");
  EXPECT_EQ(refusal(replaced(kFit, "min: 0.0, max: 0.05", "min: 0.05, max: 0.05")),
            "fit.yaml:5: fit[1].max: must be greater than min");
  EXPECT_NE(refusal(replaced(kFit, "parameter: youngs_modulus", "parameter: stiffness"))
                .find("fit.yaml:4: fit[0].parameter: unknown parameter 'stiffness' (one of "
                      "youngs_modulus, poisson_ratio"),
            std::string::npos);
  EXPECT_EQ(refusal(replaced(kFit, "sigma: 0.001", "sigma: 0")),
            "fit.yaml:7: observations[0].sigma: must be > 0, not 0");
  EXPECT_EQ(refusal(replaced(kFit, "at: [0.3, 0.03, 0.02]", "at: [0.3, 0.03]")),
            "fit.yaml:7: observations[0].at: expected [x, y, z] in m");
  EXPECT_EQ(refusal(replaced(kFit, "sigma: [0.02, 0.002]", "sigma: 0.02")),
            "fit.yaml:8: observations[1].sigma: expected [N, N m]");
  EXPECT_EQ(refusal(replaced(kFit, "reactions: beam", "reactions: beam, grasp: left")),
            "fit.yaml:8: observations[1]: give exactly one of reactions, grasp or link");
  // Bounds the parameter itself may not take, in the words of the scene reader and the bodies.
  EXPECT_EQ(refusal(replaced(kFit, "min: 1.0e4", "min: -1.0e4")),
            "fit.yaml:4: fit[0].min: must be finite and > 0 Pa (as youngs_modulus)");
  EXPECT_EQ(refusal(replaced(kFit, "min: 0.0, max: 0.05", "min: -0.01, max: 0.05")),
            "fit.yaml:5: fit[1].min: must be finite and >= 0 s (as damping_stiffness)");
  EXPECT_EQ(refusal(replaced(kFit, "parameter: damping_stiffness, min: 0.0, max: 0.05",
                             "parameter: poisson_ratio, min: 0.0, max: 0.5")),
            "fit.yaml:5: fit[1].max: must be in (-1, 0.5) (as poisson_ratio)");
  EXPECT_EQ(refusal(replaced(kFit, "min: 1.0e4", "min: lots")),
            "fit.yaml:4: fit[0].min: expected a finite number");
  EXPECT_EQ(refusal(replaced(kFit, "tf: marker_tip, ", "")),
            "fit.yaml:7: observations[0]: expected a tf or a wrench observation");
  EXPECT_EQ(refusal("bag: [\n").rfind("fit.yaml:2: not valid YAML: ", 0), 0u);
}

const std::string kScene =
    "effects: {damping: {mass: 0.0, stiffness: 0.01}}\n"
    "bodies:\n"
    "  - name: beam\n"
    "    mesh: {box: {min: [0, 0, 0], max: [0.3, 0.04, 0.04], cells: [3, 1, 1]}}\n"
    "    material: {youngs_modulus: 2.0e6, poisson_ratio: 0.3, density: 500.0}\n";

FitParameter parameter(const std::string& body, const std::string& name, double min, double max) {
  return FitParameter{body, name, min, max, "fit[0]"};
}

TEST(SceneParameter, ReadsAndSetsTheLiveTuningNames) {
  core::SceneSpec scene = io::parseScene(kScene, "scene.yaml", ".");
  const std::vector<FitParameter> fit{parameter("beam", "youngs_modulus", 1e4, 1e7),
                                      parameter("beam", "damping_stiffness", 0.0, 0.05)};
  EXPECT_EQ(firstGuess(scene, fit), (std::vector<double>{2.0e6, 0.01}));
  setParameter(scene, fit[0], 3.0e6);
  setParameter(scene, fit[1], 0.02);
  EXPECT_EQ(scene.bodies[0].material.youngs_modulus, 3.0e6);
  EXPECT_EQ(scene.effects.damping->stiffness, 0.02);
}

TEST(SceneParameter, RefusesUnknownBodiesMissingEffectsAndGuessesOutOfBounds) {
  const core::SceneSpec scene = io::parseScene(kScene, "scene.yaml", ".");
  const auto refusal = [&scene](const FitParameter& p) {
    try {
      firstGuess(scene, {p});
    } catch (const FitSpecError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(refusal(parameter("cable", "density", 1, 1e4)),
            "fit[0].body: the scene has no body 'cable' (it has beam)");
  EXPECT_EQ(refusal(parameter("beam", "friction", 0, 1)),
            "fit[0].parameter: friction needs the scene's contact effect");
  EXPECT_EQ(refusal(parameter("beam", "youngs_modulus", 1e4, 1e6)),
            "fit[0]: the scene's youngs_modulus of 'beam', 2e+06, the first guess, is outside "
            "[min, max] = [10000, 1e+06]");
}

TEST(FittedScene, WritesTheValuesWhereTheSceneHasThem) {
  const std::vector<FitParameter> fit{parameter("beam", "youngs_modulus", 1e4, 1e7),
                                      parameter("beam", "damping_stiffness", 0.0, 0.05)};
  const std::string text = fittedSceneYaml(kScene, fit, {1.234e6, 0.0123});
  const core::SceneSpec scene = io::parseScene(text, "fitted.yaml", ".");
  EXPECT_EQ(scene.bodies[0].material.youngs_modulus, 1.234e6);
  EXPECT_EQ(scene.bodies[0].material.poisson_ratio, 0.3);
  EXPECT_EQ(scene.effects.damping->stiffness, 0.0123);
}

TEST(MaterialPoint, FollowsTheElementThatHoldsIt) {
  const core::SceneSpec scene = io::parseScene(kScene, "scene.yaml", ".");
  std::vector<std::string> warnings;
  const core::Mesh mesh = io::readMeshes(scene, &warnings)[0];
  const Eigen::Vector3d at(0.17, 0.01, 0.03);
  const auto point = findMaterialPoint(mesh, at);
  ASSERT_TRUE(point);
  Eigen::VectorXd rest(3 * mesh.positions.size());
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    rest.segment<3>(3 * i) = mesh.positions[i];
  EXPECT_LT((point->position(rest) - at).norm(), 1e-12);
  // A rigid shift moves it with the body.
  Eigen::VectorXd moved = rest;
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    moved.segment<3>(3 * i) += Eigen::Vector3d(1, 2, 3);
  EXPECT_LT((point->position(moved) - at - Eigen::Vector3d(1, 2, 3)).norm(), 1e-12);
  EXPECT_FALSE(findMaterialPoint(mesh, Eigen::Vector3d(0.31, 0.01, 0.03)));
}

TEST(SimulatedSeries, InterpolatesBetweenStepsByTime) {
  SimulatedSeries series;
  series.dt = 0.01;
  for (int k = 0; k < 4; ++k) series.steps.push_back(Eigen::VectorXd::Constant(1, 10.0 * k));
  EXPECT_NEAR(series.at(0.0125)[0], 12.5, 1e-12);
  EXPECT_NEAR(series.at(0.03)[0], 30.0, 1e-12);
  EXPECT_NEAR(series.at(0.5)[0], 30.0, 1e-12);  // past the end: the last step
}

}  // namespace
}  // namespace deformable_sim::identify
