// What linearly implicit (backward) Euler does to one undamped mode x'' = -omega^2 x with step h
// (the reference README, case C2): each step multiplies the mode's complex amplitude by
// 1 / (1 - i omega h), so it turns by atan(omega h) and shrinks by 1 / sqrt(1 + (omega h)^2).
#pragma once

namespace deformable_sim::bench {

/// Numerical period 2 pi h / atan(omega h), s (omega in rad/s, h in s).
double implicitEulerPeriod(double omega, double h);

/// Amplitude ratio over one numerical period: (1 + (omega h)^2)^(-pi / atan(omega h)).
double implicitEulerAmplitudeRatioPerCycle(double omega, double h);

}  // namespace deformable_sim::bench
