// The hard cases of DESIGN.md section 8: hostile scenes stepped with the solver settings and the
// time step a scene gets by default (warped stiffness on). Each must stay finite, keep its energy
// within the work done on it, come back to rest where physics says so, and need no rescue by
// Simulation's watchdog.
//
// Hard materials: nearly incompressible, very soft beside very stiff, steel at a large step.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "hard_case_meters.h"

namespace dc = deformable_sim::core;
using namespace deformable_sim::test::hard_cases;  // NOLINT: the cases speak in its meters

// --- 4. Nearly incompressible --------------------------------------------------------------------

// A cantilever of a nearly incompressible material (nu = 0.499, lambda = 250 mu) sagging
// under gravity from rest: it must settle where the quasi-static solve puts it.
TEST(HardCases, NearlyIncompressibleCantileverSagsToItsStaticState) {
  dc::SceneSpec spec = settlingScene();
  dc::BodySpec beam =
      clampedBeam("beam", {0, -0.05, -0.05}, {0.5, 0.05, 0.05}, {1.0e6, 0.499, 1000.0});
  spec.bodies.push_back(beam);
  dc::Simulation sim = boxMeshSimulation(spec);
  dc::Simulation statics = boxMeshSimulation(spec);
  ASSERT_TRUE(statics.solveStatic()[0].converged);
  const dc::Body& reference = statics.bodies()[0];
  dc::Body& body = sim.bodies()[0];
  EnergyMeter meter(body);

  std::vector<dc::StepReport> reports;
  double previous = 0.0;  // at rest in the rest shape
  int most_iterations = 0;
  for (int s = 0; s < 1000; ++s) {
    ASSERT_NO_FATAL_FAILURE(stepChecked(sim, reports, s));
    EXPECT_TRUE(reports[0].solve.converged) << "step " << s;
    most_iterations = std::max(most_iterations, reports[0].solve.iterations);
    // Gravity is in the energy; the clamp does no work: the total can only fall.
    const double energy = meter.total(body);
    EXPECT_LE(energy, previous + 1e-9) << "step " << s;
    previous = energy;
  }
  const double sag = distanceFromRest(reference);
  const double gap = (body.positions() - reference.positions()).cwiseAbs().maxCoeff();
  std::printf(
      "[ measured ] nu = 0.499: static sag %.4g m, settled state %.3g m from it, kinetic "
      "energy %.3g J, at most %d CG iterations a step\n",
      sag, gap, body.kineticEnergy(), most_iterations);
  EXPECT_GT(sag, 1e-3);
  EXPECT_LT(gap, 1e-3 * sag);
  EXPECT_LT(body.kineticEnergy(), 1e-9 * totalMass(body) * 9.81 * sag);
  EXPECT_EQ(sim.recoveries(0), 0);
}

// --- 5. Very stiff and very soft together --------------------------------------------------------

// Two cantilevers in one simulation, E = 1e4 Pa and 1e10 Pa (a ratio of 1e6), under gravity.
TEST(HardCases, VerySoftAndVeryStiffBodiesTogether) {
  dc::SceneSpec spec = settlingScene();
  dc::BodySpec soft =
      clampedBeam("soft", {0, -0.05, -0.05}, {0.5, 0.05, 0.05}, {1.0e4, 0.3, 100.0});
  dc::BodySpec stiff =
      clampedBeam("stiff", {0, 0.45, -0.05}, {0.5, 0.55, 0.05}, {1.0e10, 0.3, 100.0});
  spec.bodies = {soft, stiff};
  dc::Simulation sim = boxMeshSimulation(spec);
  std::vector<EnergyMeter> meters{EnergyMeter(sim.bodies()[0]), EnergyMeter(sim.bodies()[1])};

  std::vector<dc::StepReport> reports;
  std::vector<double> previous{0.0, 0.0}, peak_kinetic{0.0, 0.0};
  for (int s = 0; s < 1000; ++s) {
    ASSERT_NO_FATAL_FAILURE(stepChecked(sim, reports, s));
    for (int b = 0; b < 2; ++b) {
      const dc::Body& body = sim.bodies()[b];
      EXPECT_TRUE(reports[b].solve.converged) << body.name() << " step " << s;
      const double energy = meters[b].total(body);
      EXPECT_LE(energy, previous[b] + 1e-9) << body.name() << " step " << s;
      previous[b] = energy;
      peak_kinetic[b] = std::max(peak_kinetic[b], body.kineticEnergy());
    }
  }
  for (int b = 0; b < 2; ++b) {
    const dc::Body& body = sim.bodies()[b];
    std::printf("[ measured ] %s: tip sag %.4g m, kinetic energy %.3g J of a peak %.3g J\n",
                body.name().c_str(), distanceFromRest(body), body.kineticEnergy(), peak_kinetic[b]);
    EXPECT_LT(body.kineticEnergy(), 1e-6 * peak_kinetic[b]) << body.name();
    EXPECT_EQ(sim.recoveries(b), 0) << body.name();
  }
  // The soft one hangs far down, the stiff one barely sags (linear theory: 0.9 m and 0.9 µm).
  EXPECT_GT(distanceFromRest(sim.bodies()[0]), 0.2);
  EXPECT_LT(distanceFromRest(sim.bodies()[1]), 1e-5);
}

// --- 6. A stiff body at a large step -------------------------------------------------------------

namespace {

/// The largest stable step of an explicit (central-difference) integrator for the body at rest:
/// 2 / omega_max, omega_max^2 the largest eigenvalue of K v = omega^2 M v, s.
double explicitStableStep(const dc::Body& body) {
  dc::CorotationalElasticity elasticity(body.mesh(), body.settings().material);
  elasticity.update(body.restPositions(), false);
  const int n = static_cast<int>(body.restPositions().size());
  Eigen::MatrixXd k(n, n);
  Eigen::VectorXd unit = Eigen::VectorXd::Zero(n), column(n);
  for (int j = 0; j < n; ++j) {
    unit[j] = 1.0;
    elasticity.stiffness().multiply(unit, column);
    k.col(j) = column;
    unit[j] = 0.0;
  }
  Eigen::VectorXd scale(n);  // M^-1/2
  for (int j = 0; j < n; ++j) scale[j] = 1.0 / std::sqrt(body.nodalMasses()[j / 3]);
  const Eigen::MatrixXd scaled = scale.asDiagonal() * k * scale.asDiagonal();
  const double omega_max =
      std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(scaled, Eigen::EigenvaluesOnly)
                    .eigenvalues()
                    .maxCoeff());
  return 2.0 / omega_max;
}

struct SteelRun {
  double critical_dt = 0.0, ratio = 0.0;
  double e0 = 0.0, elastic0 = 0.0, largest_rise = 0.0, final_elastic = 0.0, final_strain = 0.0;
  long recoveries = 0;
};

// A 2 cm steel cube (E = 200 GPa, 63 g) at dt = 1/30 s, free, started 0.1 % stretched along x
// and 0.1 % sheared in yz, and spinning at `spin` rad/s, for 3 s.
SteelRun steel(double spin) {
  SteelRun run;
  dc::SceneSpec spec = warpedScene();
  spec.dt = 1.0 / 30.0;
  spec.bodies.push_back(
      boxBody("steel", {0, 0, 0}, {0.02, 0.02, 0.02}, {3, 3, 3}, {2.0e11, 0.3, 7850.0}));
  dc::Simulation sim = boxMeshSimulation(spec);
  dc::Body& body = sim.bodies()[0];
  run.critical_dt = explicitStableStep(body);
  run.ratio = spec.dt / run.critical_dt;
  Eigen::VectorXd x = body.restPositions(), v(x.size());
  const Eigen::Vector3d omega = spin * Eigen::Vector3d(1.0, 2.0, 4.0).normalized();
  for (int i = 0; i < body.numNodes(); ++i) {
    const Eigen::Vector3d p = node(body.restPositions(), i) - Eigen::Vector3d::Constant(0.01);
    x.segment<3>(3 * i) += Eigen::Vector3d(1e-3 * p.x(), 1e-3 * p.z(), 0.0);
    v.segment<3>(3 * i) = omega.cross(p);
  }
  body.setState(x, v);
  EnergyMeter meter(body);
  run.e0 = meter.total(body);
  run.elastic0 = meter.elastic(body);
  EnergyLog log;
  log.start(run.e0);
  std::vector<dc::StepReport> reports;
  for (int s = 0; s < 90; ++s) {
    stepChecked(sim, reports, s);
    if (::testing::Test::HasFatalFailure()) return run;
    EXPECT_TRUE(reports[0].solve.converged) << "step " << s;
    log.add(meter.total(body));
  }
  run.largest_rise = log.largest_rise;
  run.final_elastic = meter.elastic(body);
  run.final_strain = largestStrain(body);
  run.recoveries = sim.recoveries(0);
  std::printf(
      "[ measured ] steel spinning at %g rad/s: explicit stable step %.3g s, dt = 1/30 s "
      "is %.3g times it; energy %.4g J at start, largest rise %.3g J, elastic %.3g J after "
      "3 s\n",
      spin, run.critical_dt, run.ratio, run.e0, run.largest_rise, run.final_elastic);
  return run;
}

}  // namespace

TEST(HardCases, SteelCubeAtThirtyHertzFarAboveTheExplicitStableStep) {
  const SteelRun run = steel(0.0);
  ASSERT_FALSE(HasFatalFailure());
  EXPECT_GT(run.ratio, 1e4) << "explicit stable step " << run.critical_dt << " s";
  EXPECT_EQ(run.recoveries, 0) << "explicit stable step " << run.critical_dt << " s";
  // Energy never rises above the noise of a solve to 1e-6 (its energy error is ~1e-12 e0).
  EXPECT_LE(run.largest_rise, 1e-9 * run.e0)
      << "dt is " << run.ratio << " times the explicit stable step " << run.critical_dt << " s";
  // omega dt ~ 1e4 for every mode: implicit Euler removes the strain within a step or two.
  EXPECT_LT(run.final_elastic, 1e-9 * run.elastic0);
  EXPECT_LT(run.final_strain, 1e-6);
}

// The same cube also spinning at 5 rad/s (0.17 rad a step). For steel a rotation error of 1e-4 rad
// within a step already stores more strain energy than the spin has: with the rotations of each
// step's start alone it gained energy without bound (1.4 J to above 1e25 J in 3 s).
TEST(HardCases, SpinningSteelCubeAtThirtyHertzNeverGainsEnergy) {
  const SteelRun run = steel(5.0);
  ASSERT_FALSE(HasFatalFailure());
  EXPECT_LE(run.largest_rise, 1e-9 * run.e0);
}
