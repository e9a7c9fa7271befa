#include "deformable_sim/bench/free_vibration.h"

#include <algorithm>
#include <cmath>

#include "deformable_sim/bench/damped_oscillation.h"
#include "deformable_sim/bench/heap_usage.h"
#include "deformable_sim/bench/implicit_euler_theory.h"

namespace deformable_sim::bench {

namespace {

constexpr double kReleasedLoad = 0.025;  // N, the case-A load
constexpr double kPeriodsSimulated = 2.5;
constexpr double kSamplesPerPeriod = 40.0;  // enough for the fit, few enough to keep it cheap

// The static case-A deflection of the mesh (linear FEM, direct solver), computed once.
const std::vector<Eigen::Vector3d>& releasedShape(const std::string& mesh, BenchContext& context) {
  std::vector<Eigen::Vector3d>& shape = context.ownReferences()["C2 start " + mesh];
  if (!shape.empty()) return shape;
  const ReferenceBeam& beam = context.beam(mesh);
  core::SolverSettings direct;
  direct.method = core::SolverSettings::Method::kDirect;
  core::FiniteElementBody body = beam.makeBeamBody(core::BodyEffects{}, direct);
  beam.applyTipLoad(body, kReleasedLoad);
  body.solveStatic(core::StaticSettings{});
  for (int i = 0; i < body.numNodes(); ++i) shape.emplace_back(body.positions().segment<3>(3 * i));
  return shape;
}

// Releases the beam from `start` and records its tip's z displacement every `stride` ticks (the
// start included) into `tip_uz`; the step times and memory into `run`.
void simulateRelease(const BenchSetting& setting, const ReferenceBeam& beam,
                     const std::vector<Eigen::Vector3d>& start, long ticks, long stride,
                     CaseRun& run, std::vector<double>& tip_uz) {
  Eigen::VectorXd positions(3 * start.size());
  for (size_t i = 0; i < start.size(); ++i) positions.segment<3>(3 * i) = start[i];
  run.step_ms.reserve(ticks);
  tip_uz.reserve(ticks / stride + 1);
  core::BodyEffects effects;
  effects.warping = setting.warping;
  const std::size_t heap_before = liveHeapBytes();
  core::FiniteElementBody body = beam.makeBeamBody(effects, setting.solver);
  body.setState(positions, Eigen::VectorXd::Zero(positions.size()));
  tip_uz.push_back(beam.tipDisplacement(body).z());
  for (long tick = 1; tick <= ticks; ++tick) {
    run.timeTick(body, setting.dt_s, setting.substeps);
    if (tick % stride == 0) tip_uz.push_back(beam.tipDisplacement(body).z());
  }
  run.memory_bytes = liveHeapBytes() - heap_before;
}

Comparison periodComparison(const DampedOscillation& fit, double f1_converged,
                            double expected_period, double omega, double h) {
  Comparison period;
  period.case_name = "C2_period";
  period.value = fit.period_s;
  period.reference_value = 1.0 / f1_converged;
  period.same_mesh_value = expected_period;
  period.theory_value = implicitEulerPeriod(omega, h);
  period.error = std::abs(period.value / period.reference_value - 1.0);
  period.error_same_mesh = std::abs(period.value / period.same_mesh_value - 1.0);
  period.error_definition =
      "|T/T_ref - 1| of the first bending period T (s) fitted to the tip's free vibration; ref: "
      "converged 3D f1 (hex20_L4 C3D20R); same mesh: CalculiX lumped-mass f1; theory: implicit "
      "Euler's period of that mode";
  return period;
}

Comparison dampingComparison(const DampedOscillation& fit, double omega, double h) {
  Comparison damping;
  damping.case_name = "C2_damping";
  damping.value = fit.amplitude_ratio_per_cycle;
  damping.reference_value = 1.0;  // the beam has no physical damping
  damping.same_mesh_value = 1.0;
  damping.theory_value = implicitEulerAmplitudeRatioPerCycle(omega, h);
  damping.error = 1.0 - damping.value;
  damping.error_same_mesh = damping.error;
  damping.error_definition =
      "1 - a: the fraction of the first bending mode's amplitude lost per cycle (numerical "
      "damping; the beam has none); value: a; theory: implicit Euler's a for that mode";
  return damping;
}

}  // namespace

CaseRun runFreeVibration(const BenchSetting& setting, BenchContext& context) {
  const ReferenceBeam& beam = context.beam(setting.mesh);
  const ReferenceResults& results = context.results();
  const double f1_same_mesh =
      results.value("C", "C3D4", setting.mesh, "bending mode 1", "f1_lumped_mass");
  const double f1_converged =
      results.value("C", "C3D20R", "hex20_L4", "bending mode 1", "f1_bending");
  const std::vector<Eigen::Vector3d>& start = releasedShape(setting.mesh, context);

  const double expected_period = 1.0 / f1_same_mesh;
  const long ticks = std::lround(std::ceil(kPeriodsSimulated * expected_period / setting.dt_s));
  const long stride =
      std::max(1L, std::lround(std::floor(expected_period / (kSamplesPerPeriod * setting.dt_s))));
  CaseRun run;
  std::vector<double> tip_uz;
  simulateRelease(setting, beam, start, ticks, stride, run, tip_uz);

  const DampedOscillation fit = fitDominantOscillation(tip_uz, stride * setting.dt_s);
  const double omega = 2.0 * M_PI * f1_same_mesh;
  const double h = setting.dt_s / setting.substeps;
  run.comparisons.push_back(periodComparison(fit, f1_converged, expected_period, omega, h));
  run.comparisons.push_back(dampingComparison(fit, omega, h));
  return run;
}

}  // namespace deformable_sim::bench
