// Period and decay of the dominant mode of a sampled free vibration, by Prony's method: samples
// of a sum of p damped modes obey y[n] = a_1 y[n-1] + ... + a_p y[n-p], and the roots z_k of
// z^p - a_1 z^(p-1) - ... - a_p are the modes' factors per sample, exp((-sigma_k + i omega_k) T).
// Unlike zero crossings this is not biased by the higher modes a tip release also excites (the
// reference README notes 0.5 % for its own zero-crossing periods), as long as they are fitted too.
#pragma once

#include <vector>

namespace deformable_sim::bench {

struct DampedOscillation {
  double period_s = 0.0;                   ///< 2 pi / omega of the dominant mode
  double amplitude_ratio_per_cycle = 0.0;  ///< its amplitude after one period over before
  double amplitude = 0.0;                  ///< its amplitude at the first sample
};

/// Fits `modes` damped modes to `samples` taken every `interval_s` seconds (least-squares linear
/// prediction, then least-squares amplitudes) and returns the oscillating mode with the largest
/// amplitude. For an accurate period, sample the dominant mode some 20 to 100 times per period.
/// Throws std::invalid_argument with fewer than 4 modes' worth of samples or no oscillation.
DampedOscillation fitDominantOscillation(const std::vector<double>& samples, double interval_s,
                                         int modes = 4);

}  // namespace deformable_sim::bench
