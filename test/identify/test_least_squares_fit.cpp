// The fit's uncertainty says what the data hold: its sigmas grow with residuals that scatter more
// than their sigmas, two parameters the data tell only together are correlated, and a parameter
// the residuals do not change with, or one pressed against its bound, is flagged.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "deformable_sim/identify/least_squares_fit.h"

namespace di = deformable_sim::identify;

namespace {

di::FitParameter parameter(double min, double max) {
  di::FitParameter p;
  p.body = "body";
  p.parameter = "youngs_modulus";
  p.min = min;
  p.max = max;
  return p;
}

// 400 samples of a + b = 3 with Gaussian noise of `scatter` (in units of their sigma), and one
// weak residual of a - b = 1; a third value c changes nothing.
di::ResidualFunction sumAndDifference(double scatter) {
  std::mt19937 generator(11);
  std::normal_distribution<double> gauss(0.0, scatter);
  Eigen::VectorXd noise(400);
  for (double& e : noise) e = gauss(generator);
  return [noise](const std::vector<double>& v) {
    Eigen::VectorXd r(401);
    r.head(400) = Eigen::VectorXd::Constant(400, v[0] + v[1] - 3.0) + noise;
    r[400] = 0.5 * (v[0] - v[1] - 1.0);
    return r;
  };
}

}  // namespace

TEST(LeastSquaresFit, SigmasGrowWithTheScatterAndCorrelationsShowWhatIsToldTogether) {
  const std::vector<di::FitParameter> parameters{parameter(-10, 10), parameter(-10, 10),
                                                 parameter(-10, 10)};
  const di::FitResult stated =
      di::fitLeastSquares(parameters, {0.0, 0.0, 0.5}, 401, sumAndDifference(1.0), {});
  const di::FitResult fourfold =
      di::fitLeastSquares(parameters, {0.0, 0.0, 0.5}, 401, sumAndDifference(4.0), {});
  ASSERT_TRUE(stated.converged) << stated.report;
  ASSERT_TRUE(fourfold.converged) << fourfold.report;
  EXPECT_NEAR(stated.values[0], 2.0, 0.01);
  EXPECT_NEAR(stated.values[1], 1.0, 0.01);
  // Noise of its sigma: scaled by about 1 (this draw's scatter). Four times it: the sigmas four
  // times as large.
  EXPECT_NEAR(stated.sigma_scale, 1.0, 0.1);
  EXPECT_NEAR(fourfold.sigma_scale / stated.sigma_scale, 4.0, 1e-6);
  EXPECT_NEAR(fourfold.standard_deviations[0] / stated.standard_deviations[0], 4.0, 1e-6);
  // a and b: the sum is told 400 times, the difference once and weakly. What is uncertain is
  // a - b: a higher a comes with a lower b (correlation near -1).
  EXPECT_LT(stated.correlations(0, 1), -0.9);
  EXPECT_DOUBLE_EQ(stated.correlations(0, 0), 1.0);
  // c changes no residual: flagged, no sigma, no correlation.
  EXPECT_TRUE(stated.no_effect[2]);
  EXPECT_FALSE(stated.no_effect[0]);
  EXPECT_TRUE(std::isinf(stated.standard_deviations[2]));
  EXPECT_EQ(stated.correlations(0, 2), 0.0);
  EXPECT_FALSE(stated.at_bound[0]);
}

TEST(LeastSquaresFit, AValueHeldAtItsBoundIsFlagged) {
  const std::vector<di::FitParameter> parameters{parameter(-10, 1.5), parameter(-10, 10),
                                                 parameter(-10, 10)};
  const di::FitResult result =
      di::fitLeastSquares(parameters, {0.0, 0.0, 0.5}, 401, sumAndDifference(1.0), {});
  EXPECT_NEAR(result.values[0], 1.5, 1e-9);
  EXPECT_TRUE(result.at_bound[0]);
  EXPECT_FALSE(result.at_bound[1]);
}
