// One validation per parameter (core/parameter_limits.h): what each may be, and the same word
// from the bodies and from live tuning for the same bad value.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/parameter_limits.h"
#include "deformable_sim/core/session/default_scene.h"
#include "deformable_sim/core/session/session.h"
#include "simulation_test_helpers.h"

namespace dc = deformable_sim::core;
using dc::Parameter;

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// What the body's tune() says to `value` for `parameter` ("" when they take it).
std::string bodySays(Parameter parameter, double value) {
  dc::Simulation sim = deformable_sim::test::defaultSimulation();
  dc::Body& body = sim.bodies()[0];
  dc::BodyTuning tuning;
  tuning.material = body.settings().material;
  dc::LinearElasticMaterial& material = *tuning.material;
  switch (parameter) {
    case Parameter::kYoungsModulus:
      material.youngs_modulus = value;
      break;
    case Parameter::kPoissonRatio:
      material.poisson_ratio = value;
      break;
    case Parameter::kDensity:
      material.density = value;
      break;
    case Parameter::kDampingMass:
      tuning.damping = dc::RayleighDamping{value, 0.0};
      break;
    case Parameter::kDampingStiffness:
      tuning.damping = dc::RayleighDamping{0.0, value};
      break;
    case Parameter::kSolverTolerance:
      tuning.solver_tolerance = value;
      break;
    case Parameter::kSolverMaxIterations:
      tuning.solver_max_iterations = static_cast<int>(value);
      break;
  }
  try {
    body.tune(tuning);
    return "";
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
}

// What a live tuning command says to it ("" when it is taken).
std::string tuningSays(Parameter parameter, double value) {
  const dc::SceneSpec scene = dc::defaultScene();
  const dc::BoxMeshSpec& box = *scene.bodies[0].box_mesh;
  dc::Session session(scene, {dc::makeBoxMesh(box.min, box.max, box.cells, box.element)});
  dc::TuneCommand tune;
  dc::LinearElasticMaterial material = session.simulation().bodies()[0].settings().material;
  dc::RayleighDamping damping;
  if (parameter == Parameter::kYoungsModulus) material.youngs_modulus = value;
  if (parameter == Parameter::kPoissonRatio) material.poisson_ratio = value;
  if (parameter == Parameter::kDensity) material.density = value;
  if (parameter == Parameter::kDampingMass) damping.mass = value;
  if (parameter == Parameter::kDampingStiffness) damping.stiffness = value;
  if (parameter <= Parameter::kDensity) tune.material = material;
  if (parameter == Parameter::kDampingMass || parameter == Parameter::kDampingStiffness) {
    tune.damping = damping;
  }
  if (parameter == Parameter::kSolverTolerance) tune.solver_tolerance = value;
  if (parameter == Parameter::kSolverMaxIterations) {
    tune.solver_max_iterations = static_cast<int>(value);
  }
  try {
    session.apply(tune);
  } catch (const dc::CommandError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(ParameterLimits, SayWhatEachParameterMayBe) {
  EXPECT_EQ(dc::parameterProblem(Parameter::kYoungsModulus, 1e5), "");
  EXPECT_EQ(dc::parameterProblem(Parameter::kYoungsModulus, 0.0), "must be finite and > 0 Pa");
  EXPECT_EQ(dc::parameterProblem(Parameter::kYoungsModulus, kInf), "must be finite and > 0 Pa");
  EXPECT_EQ(dc::parameterProblem(Parameter::kPoissonRatio, -0.99), "");
  EXPECT_EQ(dc::parameterProblem(Parameter::kPoissonRatio, 0.5), "must be in (-1, 0.5)");
  EXPECT_EQ(dc::parameterProblem(Parameter::kDensity, -1.0), "must be finite and > 0 kg/m^3");
  EXPECT_EQ(dc::parameterProblem(Parameter::kDampingMass, 0.0), "");
  EXPECT_EQ(dc::parameterProblem(Parameter::kDampingMass, -1e-9), "must be finite and >= 0 1/s");
  EXPECT_EQ(dc::parameterProblem(Parameter::kDampingStiffness, kInf), "must be finite and >= 0 s");
  EXPECT_EQ(dc::parameterProblem(Parameter::kSolverTolerance, 0.0), "must be finite and > 0");
  EXPECT_EQ(dc::parameterProblem(Parameter::kSolverMaxIterations, 0.0),
            "must be in 1 .. 2147483647");
  EXPECT_EQ(dc::parameterProblem(Parameter::kSolverMaxIterations, 3e9),
            "must be in 1 .. 2147483647");
  EXPECT_EQ(dc::parameterProblem(Parameter::kSolverMaxIterations, 1.0), "");
  for (int p = 0; p < dc::kParameterCount; ++p) {
    EXPECT_NE(dc::parameterProblem(static_cast<Parameter>(p), kNan), "") << p;
  }
  try {
    dc::checkParameter(Parameter::kDensity, -2.0, "material: ");
    FAIL() << "took a negative density";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "material: density is -2, it must be finite and > 0 kg/m^3");
  }
}

// The bodies and live tuning refuse the same values with the same words, naming the parameter.
TEST(ParameterLimits, BodiesAndLiveTuningSayTheSame) {
  const std::pair<Parameter, double> bad[] = {
      {Parameter::kYoungsModulus, -5.0},     {Parameter::kPoissonRatio, 0.5},
      {Parameter::kDensity, kNan},           {Parameter::kDampingMass, -1.0},
      {Parameter::kDampingStiffness, kInf},  {Parameter::kSolverTolerance, 0.0},
      {Parameter::kSolverMaxIterations, 0.0}};
  for (const auto& [parameter, value] : bad) {
    const std::string problem = dc::parameterProblem(parameter, value);
    const std::string name = dc::parameterName(parameter);
    ASSERT_NE(problem, "") << name;
    const std::string body = bodySays(parameter, value), tuning = tuningSays(parameter, value);
    EXPECT_NE(body.find(name + " is "), std::string::npos) << body;
    EXPECT_NE(body.find(problem), std::string::npos) << body;
    EXPECT_NE(tuning.find(name + " is "), std::string::npos) << tuning;
    EXPECT_NE(tuning.find(problem), std::string::npos) << tuning;
  }
  for (int p = 0; p < dc::kParameterCount; ++p) {
    const Parameter parameter = static_cast<Parameter>(p);
    const double good = parameter == Parameter::kSolverMaxIterations ? 20.0 : 0.2;
    EXPECT_EQ(bodySays(parameter, good), "") << p;
    EXPECT_EQ(tuningSays(parameter, good), "") << p;
  }
}
