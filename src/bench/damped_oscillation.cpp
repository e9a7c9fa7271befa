#include "deformable_sim/bench/damped_oscillation.h"

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <stdexcept>

namespace deformable_sim::bench {

DampedOscillation fitDominantOscillation(const std::vector<double>& samples, double interval_s,
                                         int modes) {
  const int order = 2 * modes;  // a real oscillating mode is a conjugate pair of roots
  const int count = static_cast<int>(samples.size());
  if (modes < 1 || count < 4 * order || !(interval_s > 0.0)) {
    throw std::invalid_argument("oscillation fit: need at least " + std::to_string(8 * modes) +
                                " samples and a positive interval, got " + std::to_string(count));
  }
  // Linear prediction y[n] = sum_k a_k y[n-k], least squares over every n >= order. The SVD
  // copes with a signal that has fewer modes than asked for (a rank-deficient system).
  Eigen::MatrixXd past(count - order, order);
  Eigen::VectorXd next(count - order);
  for (int r = 0; r < count - order; ++r) {
    for (int k = 0; k < order; ++k) past(r, k) = samples[order + r - 1 - k];
    next[r] = samples[order + r];
  }
  const Eigen::VectorXd a = past.bdcSvd(Eigen::ComputeThinU | Eigen::ComputeThinV).solve(next);
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(order, order);
  companion.row(0) = a.transpose();
  companion.diagonal(-1).setOnes();
  const Eigen::VectorXcd roots =
      Eigen::EigenSolver<Eigen::MatrixXd>(companion, false).eigenvalues();

  // Amplitudes: y[n] = sum_k c_k z_k^n in the least-squares sense.
  Eigen::MatrixXcd powers(count, order);
  for (int k = 0; k < order; ++k) {
    std::complex<double> z_n = 1.0;
    for (int n = 0; n < count; ++n, z_n *= roots[k]) powers(n, k) = z_n;
  }
  const Eigen::VectorXcd y =
      Eigen::VectorXd::Map(samples.data(), count).cast<std::complex<double>>();
  const Eigen::VectorXcd c = powers.bdcSvd(Eigen::ComputeThinU | Eigen::ComputeThinV).solve(y);

  // Roots the data does not need (more modes asked for than the signal has) get no amplitude.
  const double negligible =
      1e-9 * Eigen::VectorXd::Map(samples.data(), count).cwiseAbs().maxCoeff();
  DampedOscillation dominant;
  dominant.amplitude = negligible;
  for (int k = 0; k < order; ++k) {
    const double turn = std::arg(roots[k]);  // radians per sample
    if (!(turn > 1e-9)) continue;            // real roots and the negative half of each pair
    const double amplitude = 2.0 * std::abs(c[k]);
    if (amplitude <= dominant.amplitude) continue;
    const double samples_per_period = 2.0 * M_PI / turn;
    dominant.amplitude = amplitude;
    dominant.period_s = samples_per_period * interval_s;
    dominant.amplitude_ratio_per_cycle = std::pow(std::abs(roots[k]), samples_per_period);
  }
  if (!(dominant.period_s > 0.0)) throw std::invalid_argument("oscillation fit: no oscillation");
  return dominant;
}

}  // namespace deformable_sim::bench
