// What each parameter of a body's material, damping and solver may be, written once: the scene
// reader, live tuning and the bodies check against these and say the same thing.
#pragma once

#include <optional>
#include <string>

namespace deformable_sim::core {

enum class Parameter {
  kYoungsModulus,
  kPoissonRatio,
  kDensity,
  kDampingMass,
  kDampingStiffness,
  kSolverTolerance,
  kSolverMaxIterations,  // keep last: kParameterCount counts up to it
};
constexpr int kParameterCount = static_cast<int>(Parameter::kSolverMaxIterations) + 1;

/// Its name in scenes and live tuning: youngs_modulus, poisson_ratio, density, damping_mass,
/// damping_stiffness, solver_tolerance, solver_max_iterations.
const char* parameterName(Parameter parameter);
/// The parameter of that name, or nullopt.
std::optional<Parameter> parameterNamed(const std::string& name);

/// Why `value` cannot be `parameter` ("must be finite and > 0 Pa"), or "" when it can. Written
/// so that NaN fails every range.
std::string parameterProblem(Parameter parameter, double value);

/// Throws std::invalid_argument "<context><name> is <value>, it must be ..." when `value` cannot
/// be `parameter`.
void checkParameter(Parameter parameter, double value, const std::string& context = "");

/// Rayleigh damping's two coefficients, and the iterative solver's limits, checked as above.
void checkDamping(double mass, double stiffness, const std::string& context = "");
void checkSolverLimits(double tolerance, int max_iterations, const std::string& context = "");

}  // namespace deformable_sim::core
