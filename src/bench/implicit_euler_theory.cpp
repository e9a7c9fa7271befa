#include "deformable_sim/bench/implicit_euler_theory.h"

#include <cmath>

namespace deformable_sim::bench {

double implicitEulerPeriod(double omega, double h) { return 2.0 * M_PI * h / std::atan(omega * h); }

double implicitEulerAmplitudeRatioPerCycle(double omega, double h) {
  const double wh = omega * h;
  return std::pow(1.0 + wh * wh, -M_PI / std::atan(wh));
}

}  // namespace deformable_sim::bench
