// The settings a user may change while a simulation runs (the node's dynamic_reconfigure), and
// the tuning commands that take a simulation from one set of them to another. Nothing here
// checks values: the session refuses a command whose values are impossible, and changes nothing.
#pragma once

#include <string>
#include <vector>

#include "deformable_sim/core/session/session.h"

namespace deformable_sim::core {

/// The rates (Hz) a driver's timer may tick at: a step of a thousand seconds at the slowest, a
/// period a timer can still keep at the fastest.
constexpr double kMinRate = 1.0e-3;
constexpr double kMaxRate = 1.0e5;

struct LiveSettings {
  std::string body;  ///< the body the material, damping and solver settings apply to; "": all
  double youngs_modulus = 0.0;     ///< Pa
  double poisson_ratio = 0.0;      ///<
  double density = 0.0;            ///< kg/m^3
  double damping_mass = 0.0;       ///< 1/s
  double damping_stiffness = 0.0;  ///< s
  double solver_tolerance = 0.0;   ///< relative residual
  int solver_max_iterations = 0;   ///<
  double rate = 0.0;               ///< Hz of the node's timer
};

/// The settings of `body` now, at the node's rate `rate`.
LiveSettings liveSettings(const Body& body, double rate);

/// The commands that change what differs between `before` and `after`: per body (every body, or
/// the one `after.body` names), then the step dt = 1 / (rate substeps) when the rate changed.
/// Throws CommandError when `after.body` names no body, or when the rate is outside
/// [kMinRate, kMaxRate].
std::vector<TuneCommand> tuneCommands(const Simulation& simulation, const LiveSettings& before,
                                      const LiveSettings& after, int substeps);

}  // namespace deformable_sim::core
