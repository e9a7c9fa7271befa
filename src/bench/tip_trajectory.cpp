#include "deformable_sim/bench/tip_trajectory.h"

#include <cmath>
#include <stdexcept>

#include "deformable_sim/bench/heap_usage.h"

namespace deformable_sim::bench {

namespace {

constexpr double kDuration = 1.0;  // s
constexpr double kLoadAlpha = 1.0;
constexpr int kSamples = 30;  // kDuration / kTrajectorySampleInterval
constexpr int kConvergedTicksPerSample = 64;

using TipPath = std::vector<Eigen::Vector3d>;

long ticksPerSample(double dt) {
  const long ticks = std::lround(kTrajectorySampleInterval / dt);
  if (ticks < 1 || std::abs(ticks * dt - kTrajectorySampleInterval) > 1e-12) {
    throw std::invalid_argument("trajectory: dt must divide 1/30 s");
  }
  return ticks;
}

// Runs the trajectory and samples the tip; times every tick into `run` when it is given.
TipPath simulate(const ReferenceBeam& beam, bool warping, const core::SolverSettings& solver,
                 double dt, int substeps, CaseRun* run) {
  const long ticks = ticksPerSample(dt);
  if (run) run->step_ms.reserve(ticks * kSamples);
  TipPath path;
  path.reserve(kSamples);
  core::BodyEffects effects;
  effects.warping = warping;
  const std::size_t heap_before = liveHeapBytes();
  core::FiniteElementBody body = beam.makeBeamBody(effects, solver);
  beam.applyTipLoad(body, largeDeflectionLoad(kLoadAlpha));
  for (int sample = 0; sample < kSamples; ++sample) {
    for (long tick = 0; tick < ticks; ++tick) {
      if (run) {
        run->timeTick(body, dt, substeps);
      } else {
        for (int s = 0; s < substeps; ++s) body.step(dt / substeps);
      }
    }
    path.push_back(beam.tipDisplacement(body));
  }
  if (run) run->memory_bytes = liveHeapBytes() - heap_before;
  return path;
}

const TipPath& convergedPath(const std::string& mesh, BenchContext& context) {
  TipPath& path = context.ownReferences()["T converged " + mesh];
  if (!path.empty()) return path;
  core::SolverSettings direct;
  direct.method = core::SolverSettings::Method::kDirect;
  const ReferenceBeam& beam = context.beam(mesh);
  const double fine = kTrajectorySampleInterval / kConvergedTicksPerSample;
  const TipPath with_h = simulate(beam, true, direct, fine, 1, nullptr);
  const TipPath with_2h = simulate(beam, true, direct, 2.0 * fine, 1, nullptr);
  // x(h) = x* + c h + O(h^2), so 2 x(h) - x(2h) = x* + O(h^2).
  for (int k = 0; k < kSamples; ++k) path.push_back(2.0 * with_h[k] - with_2h[k]);
  return path;
}

}  // namespace

CaseRun runTrajectory(const BenchSetting& setting, BenchContext& context) {
  const TipPath& converged = convergedPath(setting.mesh, context);
  CaseRun run;
  const TipPath path = simulate(context.beam(setting.mesh), setting.warping, setting.solver,
                                setting.dt_s, setting.substeps, &run);
  double squared_sum = 0.0, largest = 0.0;
  for (int k = 0; k < kSamples; ++k) {
    squared_sum += (path[k] - converged[k]).squaredNorm();
    largest = std::max(largest, converged[k].norm());
  }
  Comparison c;
  c.case_name = "T_trajectory";
  c.value = path.back().z();
  c.reference_value = converged.back().z();
  c.same_mesh_value = c.reference_value;
  c.theory_value = std::nan("");
  c.error = std::sqrt(squared_sum / kSamples) / largest;
  c.error_same_mesh = c.error;
  c.error_definition =
      "RMS over t = 1/30 ... 1 s of |u(t) - u_ref(t)| / max |u_ref| for the tip face's area-mean "
      "displacement after a sudden alpha = 1 tip load; value: uz(1 s); ref: converged run on the "
      "same mesh (warped, direct, h = 1/1920 and 1/960 s, Richardson)";
  run.comparisons.push_back(c);
  return run;
}

}  // namespace deformable_sim::bench
