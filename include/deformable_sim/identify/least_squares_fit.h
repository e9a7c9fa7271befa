// Bounded nonlinear least squares over a few scene parameters (Ceres Solver): positive
// parameters on a log scale, the Jacobian by forward differences whose re-simulations run side by
// side, and each parameter's 1-sigma and their correlations from the Jacobian at the optimum.
// The sigmas are scaled by the weighted RMS residual where it exceeds 1: residuals that scatter
// more than the sigmas given say the noise was larger than stated (or the model is off), and a
// 1-sigma taken from the stated noise alone would claim more than the data holds.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "deformable_sim/identify/fit_spec.h"

namespace deformable_sim::identify {

/// Residuals already weighted by their sigma, for the parameters' values. Called from several
/// threads at once.
using ResidualFunction = std::function<Eigen::VectorXd(const std::vector<double>& values)>;

struct FitOptions {
  int threads = 1;          ///< residual evaluations at once
  int max_iterations = 30;  ///< Levenberg-Marquardt iterations
  /// Told after every iteration: its number, the cost (half the sum of squares), the values.
  std::function<void(int iteration, double cost, const std::vector<double>& values)> progress;
};

struct FitResult {
  std::vector<double> values;
  /// 1 sigma, from (J^T J)^-1 at the optimum times sigma_scale; infinite where no effect.
  std::vector<double> standard_deviations;
  /// The weighted RMS residual over the degrees of freedom, sqrt(2 cost / (m - n)), where it
  /// exceeds 1 (else 1): what the sigmas were scaled by.
  double sigma_scale = 1.0;
  Eigen::MatrixXd correlations;  ///< of the values (in the solver's coordinates), n x n
  /// Per parameter: the residuals do not change with it (a zero column of the Jacobian).
  std::vector<bool> no_effect;
  /// Per parameter: it ended at its min or max.
  std::vector<bool> at_bound;
  bool converged = false;
  std::string report;  ///< the solver's reason for stopping
  double initial_cost = 0.0, final_cost = 0.0;
  int iterations = 0;
};

FitResult fitLeastSquares(const std::vector<FitParameter>& parameters,
                          const std::vector<double>& guess, long residual_count,
                          const ResidualFunction& residuals, const FitOptions& options);

}  // namespace deformable_sim::identify
