#include "deformable_sim/core/elements/parameter_limits.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace deformable_sim::core {

const char* parameterName(Parameter parameter) {
  switch (parameter) {
    case Parameter::kYoungsModulus:
      return "youngs_modulus";
    case Parameter::kPoissonRatio:
      return "poisson_ratio";
    case Parameter::kDensity:
      return "density";
    case Parameter::kDampingMass:
      return "damping_mass";
    case Parameter::kDampingStiffness:
      return "damping_stiffness";
    case Parameter::kSolverTolerance:
      return "solver_tolerance";
    case Parameter::kSolverMaxIterations:
      return "solver_max_iterations";
  }
  return "?";
}

std::optional<Parameter> parameterNamed(const std::string& name) {
  for (int p = 0; p < kParameterCount; ++p) {
    if (name == parameterName(static_cast<Parameter>(p))) return static_cast<Parameter>(p);
  }
  return std::nullopt;
}

std::string parameterProblem(Parameter parameter, double value) {
  const bool finite = std::isfinite(value);
  switch (parameter) {
    case Parameter::kYoungsModulus:
      return finite && value > 0.0 ? "" : "must be finite and > 0 Pa";
    case Parameter::kPoissonRatio:
      return value > -1.0 && value < 0.5 ? "" : "must be in (-1, 0.5)";
    case Parameter::kDensity:
      return finite && value > 0.0 ? "" : "must be finite and > 0 kg/m^3";
    case Parameter::kDampingMass:
      return finite && value >= 0.0 ? "" : "must be finite and >= 0 1/s";
    case Parameter::kDampingStiffness:
      return finite && value >= 0.0 ? "" : "must be finite and >= 0 s";
    case Parameter::kSolverTolerance:
      return finite && value > 0.0 ? "" : "must be finite and > 0";
    case Parameter::kSolverMaxIterations:
      return value >= 1.0 && value <= 2147483647.0 ? "" : "must be in 1 .. 2147483647";
  }
  return "unknown parameter";
}

void checkParameter(Parameter parameter, double value, const std::string& context) {
  const std::string problem = parameterProblem(parameter, value);
  if (problem.empty()) return;
  std::ostringstream message;
  message << context << parameterName(parameter) << " is " << value << ", it " << problem;
  throw std::invalid_argument(message.str());
}

void checkDamping(double mass, double stiffness, const std::string& context) {
  checkParameter(Parameter::kDampingMass, mass, context);
  checkParameter(Parameter::kDampingStiffness, stiffness, context);
}

void checkSolverLimits(double tolerance, int max_iterations, const std::string& context) {
  checkParameter(Parameter::kSolverTolerance, tolerance, context);
  checkParameter(Parameter::kSolverMaxIterations, max_iterations, context);
}

}  // namespace deformable_sim::core
