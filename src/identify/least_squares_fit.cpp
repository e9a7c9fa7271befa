#include "deformable_sim/identify/least_squares_fit.h"

#include <ceres/ceres.h>

#include <Eigen/Cholesky>
#include <atomic>
#include <cmath>
#include <exception>
#include <thread>

namespace deformable_sim::identify {

namespace {

// The solver's coordinate of a parameter: log(value) when its bounds are positive (E spans
// decades), else the value itself.
struct Coordinate {
  bool log = false;
  double lower = 0.0, upper = 0.0;

  explicit Coordinate(const FitParameter& p)
      : log(p.min > 0.0),
        lower(log ? std::log(p.min) : p.min),
        upper(log ? std::log(p.max) : p.max) {}
  double from(double value) const { return log ? std::log(value) : value; }
  double to(double x) const { return log ? std::exp(x) : x; }
  /// Forward-difference step: 0.1 % of the value (log) or of the range.
  double step() const { return log ? 1.0e-3 : 1.0e-3 * (upper - lower); }
};

// Every point's residuals, `threads` evaluations at a time; an empty vector for one that threw.
std::vector<Eigen::VectorXd> evaluateAll(const ResidualFunction& f,
                                         const std::vector<std::vector<double>>& points,
                                         int threads) {
  std::vector<Eigen::VectorXd> results(points.size());
  std::atomic<std::size_t> next{0};
  const auto work = [&] {
    for (std::size_t k = next++; k < points.size(); k = next++) {
      try {
        results[k] = f(points[k]);
      } catch (const std::exception&) {
        results[k] = Eigen::VectorXd();  // e.g. an impossible material: a failed trial step
      }
    }
  };
  std::vector<std::thread> pool;
  const int count = std::max(1, std::min<int>(threads, static_cast<int>(points.size())));
  for (int t = 1; t < count; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  return results;
}

class SimulationCost : public ceres::CostFunction {
 public:
  SimulationCost(std::vector<Coordinate> coordinates, long residual_count,
                 const ResidualFunction& f, int threads)
      : coordinates_(std::move(coordinates)), f_(f), threads_(threads) {
    set_num_residuals(static_cast<int>(residual_count));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(coordinates_.size()));
  }

  std::vector<double> values(const double* x) const {
    std::vector<double> v;
    for (std::size_t i = 0; i < coordinates_.size(); ++i) v.push_back(coordinates_[i].to(x[i]));
    return v;
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const double* x = parameters[0];
    const std::size_t n = coordinates_.size();
    // Ceres asks for the Jacobian at the point whose residuals it just had: kept, not re-run.
    const bool known = jacobians && jacobians[0] && last_x_ == std::vector<double>(x, x + n);
    std::vector<std::vector<double>> points;
    if (!known) points.push_back(values(x));
    std::vector<double> steps(n, 0.0);
    if (jacobians && jacobians[0]) {
      for (std::size_t i = 0; i < n; ++i) {
        std::vector<double> shifted(x, x + n);
        const Coordinate& c = coordinates_[i];
        steps[i] = x[i] + c.step() <= c.upper ? c.step() : -c.step();
        shifted[i] += steps[i];
        points.push_back(values(shifted.data()));
      }
    }
    std::vector<Eigen::VectorXd> r = evaluateAll(f_, points, threads_);
    if (known) r.insert(r.begin(), last_residuals_);
    for (const Eigen::VectorXd& one : r) {
      if (one.size() != num_residuals() || !one.allFinite()) return false;
    }
    last_x_.assign(x, x + n);
    last_residuals_ = r[0];
    Eigen::Map<Eigen::VectorXd>(residuals, num_residuals()) = r[0];
    if (jacobians && jacobians[0]) {
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> J(
          jacobians[0], num_residuals(), static_cast<Eigen::Index>(n));
      for (std::size_t i = 0; i < n; ++i) J.col(i) = (r[i + 1] - r[0]) / steps[i];
    }
    return true;
  }

 private:
  std::vector<Coordinate> coordinates_;
  const ResidualFunction& f_;
  int threads_;
  // The last point evaluated and its residuals (Ceres evaluates from one thread).
  mutable std::vector<double> last_x_;
  mutable Eigen::VectorXd last_residuals_;
};

class ProgressCallback : public ceres::IterationCallback {
 public:
  ProgressCallback(const SimulationCost& cost, const double* x, const FitOptions& options)
      : cost_(cost), x_(x), options_(options) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    if (options_.progress) options_.progress(summary.iteration, summary.cost, cost_.values(x_));
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const SimulationCost& cost_;
  const double* x_;
  const FitOptions& options_;
};

// Each value's 1 sigma and their correlations, into `result`: from (J^T J)^-1 in the solver's
// coordinates (the residuals are weighted by their sigma), over the parameters that change the
// residuals at all, scaled by result.sigma_scale, and taken through the log where there is one.
void uncertainty(const SimulationCost& cost, const std::vector<Coordinate>& coordinates,
                 std::vector<double> x, FitResult& result) {
  const int m = cost.num_residuals(), n = static_cast<int>(x.size());
  result.standard_deviations.assign(n, std::numeric_limits<double>::infinity());
  result.correlations = Eigen::MatrixXd::Identity(n, n);
  result.no_effect.assign(n, false);
  Eigen::VectorXd r(m);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> J(m, n);
  const double* parameters[] = {x.data()};
  double* jacobians[] = {J.data()};
  if (!cost.Evaluate(parameters, r.data(), jacobians)) return;
  std::vector<int> effective;
  for (int i = 0; i < n; ++i) {
    result.no_effect[i] = J.col(i).squaredNorm() == 0.0;
    if (!result.no_effect[i]) effective.push_back(i);
  }
  const int k = static_cast<int>(effective.size());
  Eigen::MatrixXd information(k, k);
  for (int a = 0; a < k; ++a) {
    for (int b = 0; b < k; ++b) information(a, b) = J.col(effective[a]).dot(J.col(effective[b]));
  }
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(information);
  if (ldlt.info() != Eigen::Success) return;
  const Eigen::MatrixXd covariance = ldlt.solve(Eigen::MatrixXd::Identity(k, k));
  for (int a = 0; a < k; ++a) {
    const int i = effective[a];
    const double s = result.sigma_scale * std::sqrt(std::max(covariance(a, a), 0.0));
    result.standard_deviations[i] = coordinates[i].log ? coordinates[i].to(x[i]) * s : s;
    for (int b = 0; b < k; ++b) {
      result.correlations(i, effective[b]) =
          covariance(a, b) / std::sqrt(covariance(a, a) * covariance(b, b));
    }
  }
}

}  // namespace

FitResult fitLeastSquares(const std::vector<FitParameter>& parameters,
                          const std::vector<double>& guess, long residual_count,
                          const ResidualFunction& residuals, const FitOptions& options) {
  std::vector<Coordinate> coordinates;
  std::vector<double> x;
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    coordinates.emplace_back(parameters[i]);
    x.push_back(coordinates.back().from(guess[i]));
  }
  auto* cost = new SimulationCost(coordinates, residual_count, residuals, options.threads);
  ceres::Problem problem;
  problem.AddResidualBlock(cost, nullptr, x.data());
  for (std::size_t i = 0; i < x.size(); ++i) {
    problem.SetParameterLowerBound(x.data(), static_cast<int>(i), coordinates[i].lower);
    problem.SetParameterUpperBound(x.data(), static_cast<int>(i), coordinates[i].upper);
  }
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options.max_iterations;
  solver.function_tolerance = 1.0e-8;
  solver.parameter_tolerance = 1.0e-6;
  solver.logging_type = ceres::SILENT;
  solver.update_state_every_iteration = true;
  ProgressCallback callback(*cost, x.data(), options);
  solver.callbacks.push_back(&callback);
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);

  FitResult result;
  result.values = cost->values(x.data());
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  result.report = summary.message;
  result.initial_cost = summary.initial_cost;
  result.final_cost = summary.final_cost;
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  const long freedom = residual_count - static_cast<long>(x.size());
  if (freedom > 0) {
    result.sigma_scale =
        std::max(1.0, std::sqrt(2.0 * result.final_cost / static_cast<double>(freedom)));
  }
  for (std::size_t i = 0; i < x.size(); ++i) {
    // Within a millionth of its range of a bound is at it.
    const double room = 1e-6 * (coordinates[i].upper - coordinates[i].lower);
    result.at_bound.push_back(x[i] <= coordinates[i].lower + room ||
                              x[i] >= coordinates[i].upper - room);
  }
  uncertainty(*cost, coordinates, x, result);
  return result;
}

}  // namespace deformable_sim::identify
