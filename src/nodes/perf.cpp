// deformable_sim_perf: what a step costs, on meshes of about 1k, 10k, 50k and 100k tetrahedra
// (Google Benchmark; report medians: --benchmark_repetitions=5
// --benchmark_report_aggregates_only=true). The scene is perf/cantilever.h: a soft cantilever
// swinging under gravity, dt = 0.01 s, CG to a relative residual of 1e-6.
//
// Step/<mesh>/<preconditioner>/<threads>: the whole implicit step (preconditioner 0 block-Jacobi,
// 1 two-level, 2 an LDL^T factorization of A refreshed every 10 solves, on the two smaller
// meshes); counters give its phases in ms (rotations, assembly, the preconditioner's refresh,
// CG, and the rest: right-hand side, energies, state update), CG iterations and the heap a body
// keeps per tetrahedron. MatVec/<tets>: one product with the assembled K', the unit of a CG
// iteration.
//
// BulletStep/<mesh>/<corotated_force>: the same cantilever and 0.01 s step in Bullet's deformable
// solver (perf/bullet_peer.h) on the two smaller meshes, ms per 0.01 s like Step. 0:
// btDeformableLinearElasticityForce, linear elasticity in the rotated frame with implicit Euler
// and CG, the core's model and scheme, one Bullet step. 1: btDeformableCorotatedForce, whose
// elasticity Bullet integrates explicitly, in several Bullet steps: a few more than the fewest
// found stable (doc/performance.md says how many blew up). One Newton
// iteration a Bullet step (Bullet's default five repeat the solve: see bullet_peer.h). Counters:
// Bullet steps and CG iterations per 0.01 s.
//
// EffectCost/<effect>: what each effect adds to a step on the 9k mesh. The base is linear FEM with
// no effect, swinging under a 50 N tip load (so that every variant moves); each variant turns on
// one effect (1 warping, 2 gravity, 3 damping, 4 plasticity, 5 reactions, 6 contact with a floor
// 1 cm under the beam, 7 strain colouring: one nodalStrain of the mesh, as the node does per
// marker update; 8 all of them). An effect changes the motion too, so compare the CG iterations.
// Each variant is a one-body Simulation, stepped as the node steps it: the base includes what
// every step pays (the step's copy of where it began, for the watchdog, and its finiteness checks).
//
// LawStep/<law>/<mesh>: Step with the two-level preconditioner on one thread, under warped
// stiffness (0) or Neo-Hookean elasticity (1; core/materials), on the two smaller meshes; its
// solves counter is Newton's iterations per step.
//
// ModelStep/<model>/<mesh>: a step of a free rigid (0) or pseudo-rigid (1) body of the cantilever's
// mesh under gravity and the tip load, on 1.5k and 98k tetrahedra: the same cost for both.
//
// ContactCost/<bodies>/<contact>/<direct>/<threads>: a step of the whole scene of
// perf/blocks_on_floor.h, 1, 5 or 20 blocks of 1,536 tetrahedra side by side on a floor: 0,
// contact with the floor only; 1, and between bodies; 2, and each block with itself (the cost of
// the search alone: a block resting on a floor does not meet itself); solved by CG (0) or the
// direct solver (1), on 1 or 2 threads (the bodies' steps side by side, contact between them
// found and answered a body to a thread); timed over 20 steps after 40 to settle. Counters:
// pairs between bodies per step, and the linear solves per step that contact between bodies
// took for the bodies' answers (three per node that started touching, or all again where a
// body's kept answers went stale).
//
// ManyBodies/<bodies>/<threads>: 1, 5 or 20 such blocks hanging apart (clamped at one face, no
// floor, no contact), on 1 or 2 threads: the bodies step side by side.
//
// VoxelizeScan/<side_cells>/<closed>: a body's grid from perf/scan_blob.h's closed, bumpy blob of
// 69,732 triangles (core::voxelize, with voxelGridFor, on one thread): 26 cells along its longest
// side make about 10k cells, 58 about 100k. closed 1: as it is, asked by ray crossings; 0: with one
// triangle left out, so open: the rays count with a cap over the hole, less the cap's own winding
// number (core/surface_bodies/grid_inside.h). Counters: cells, triangles.
//
// CheckScan: core::checkSurface on the same blob (copied each time, as a body's surface is):
// zero-area, repeated and misoriented triangles, edges, shells and crossing pairs. Counters:
// triangles, crossings.
//
// MachineRead/<KiB> and MachineFma: what one core does at best (perf/machine_floor.h), the
// floors under the step's parts in doc/performance.md. Counters: GB/s read from an array of that
// size, read again and again (in L1, L2, L3 or memory by its size); GFlop/s of multiply-adds.
#include <benchmark/benchmark.h>

#include <array>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <tuple>
#include <utility>
#include <vector>

#include "deformable_sim/bench/heap_usage.h"
#include "deformable_sim/core/bodies/reduced_body.h"
#include "deformable_sim/core/contact/contact.h"
#include "deformable_sim/core/elements/loads.h"
#include "deformable_sim/core/outputs/strain.h"
#include "deformable_sim/core/session/simulation.h"
#include "deformable_sim/core/surface_bodies/surface_check.h"
#include "deformable_sim/core/surface_bodies/voxelization.h"
#include "deformable_sim/perf/blocks_on_floor.h"
#include "deformable_sim/perf/bullet_peer.h"
#include "deformable_sim/perf/cantilever.h"
#include "deformable_sim/perf/machine_floor.h"
#include "deformable_sim/perf/scan_blob.h"

namespace {

namespace core = deformable_sim::core;
namespace perf = deformable_sim::perf;

constexpr const char* kUsage =
    "usage: deformable_sim_perf [--benchmark_filter=REGEX] [--benchmark_repetitions=N]\n"
    "                           [--benchmark_report_aggregates_only=true] [--benchmark_...]\n"
    "  What a step costs, per mesh size, preconditioner, thread count, effect, body model and\n"
    "  number of bodies, next to Bullet's deformable solver (the families: the comment at the top\n"
    "  of src/nodes/perf.cpp; results: doc/performance.md). Report medians:\n"
    "  --benchmark_repetitions=5 --benchmark_report_aggregates_only=true\n"
    "  --benchmark_list_tests=true lists them; --benchmark_filter=Step/ runs only those.\n"
    "  --help, -h   print this usage and Google Benchmark's flags, and exit\n"
    "Google Benchmark's flags:\n";

// About 1.5k, 9k, 49k and 98k tetrahedra; 9 216 is the size peers are usually quoted at.
const std::array<Eigen::Vector3i, 4> kCells = {Eigen::Vector3i(16, 4, 4), Eigen::Vector3i(24, 8, 8),
                                               Eigen::Vector3i(48, 13, 13),
                                               Eigen::Vector3i(64, 16, 16)};
// From rest into the swing, so that every step solves something and the warm start's store of
// previous solutions (32) is full.
constexpr int kWarmUpSteps = 40;
constexpr int kTimedSteps = 200;

struct Swinging {
  std::unique_ptr<core::FiniteElementBody> body;
  double bytes_per_tetrahedron = 0.0;
};

// One swinging body per (mesh, preconditioner, threads, law), kept across benchmarks and
// repetitions (its buffers and coarse space are made once); Step restarts its swing on every run.
Swinging& swinging(int mesh, core::SolverSettings::Preconditioner preconditioner, int threads,
                   core::ElasticLaw law = core::ElasticLaw::kWarpedStiffness) {
  static std::map<std::tuple<int, int, int, int>, Swinging> bodies;
  Swinging& s = bodies[{mesh, static_cast<int>(preconditioner), threads, static_cast<int>(law)}];
  if (!s.body) {
    perf::Cantilever cantilever = perf::makeCantilever(kCells[mesh]);
    cantilever.solver.preconditioner = preconditioner;
    cantilever.solver.threads = threads;
    cantilever.material.law = law;
    const std::size_t before = deformable_sim::bench::liveHeapBytes();
    s.body = std::make_unique<core::FiniteElementBody>(perf::makeCantileverBody(cantilever));
    s.body->step(cantilever.dt);  // buffers and the coarse space are made in the first step
    s.bytes_per_tetrahedron = static_cast<double>(deformable_sim::bench::liveHeapBytes() - before) /
                              cantilever.mesh.numTetrahedra();
  }
  return s;
}

// Back to rest and into the swing: every run, repetition and build times the same steps of the
// same motion (a swing left running comes to rest over thousands of steps, where the relative
// residual asks for more iterations: those would depend on how long the benchmark ran).
void restartSwing(core::Body& body) {
  body.setState(body.restPositions(), Eigen::VectorXd::Zero(body.restPositions().size()));
  for (int k = 0; k < kWarmUpSteps; ++k) body.step(0.01);
}

// Times the steps of `s`'s swing; counters as the comment at the top says.
void timeSwingSteps(benchmark::State& state, Swinging& s) {
  restartSwing(*s.body);
  core::StepTimes sum;
  double iterations = 0.0, solves = 0.0, splits = 0.0;
  bool converged = true;
  for (auto _ : state) {
    const core::StepReport report = s.body->step(0.01);
    sum.rotations += report.times.rotations;
    sum.assembly += report.times.assembly;
    sum.solve += report.times.solve;
    sum.preconditioner += report.times.preconditioner;
    sum.total += report.times.total;
    iterations += report.solve.iterations;
    solves += report.solves;
    splits += report.splits;
    converged = converged && report.solve.converged;
  }
  const double steps = static_cast<double>(state.iterations());
  state.counters["tets"] = s.body->mesh().numTetrahedra();
  state.counters["rotations_ms"] = 1e3 * sum.rotations / steps;
  state.counters["assembly_ms"] = 1e3 * sum.assembly / steps;
  state.counters["preconditioner_ms"] = 1e3 * sum.preconditioner / steps;
  state.counters["cg_ms"] = 1e3 * (sum.solve - sum.preconditioner) / steps;
  state.counters["rest_ms"] = 1e3 * (sum.total - sum.rotations - sum.assembly - sum.solve) / steps;
  state.counters["cg_iterations"] = iterations / steps;
  // More than one: steps solved again with end rotations, or Newton iterations of a hyperelastic
  // law.
  state.counters["solves"] = solves / steps;
  state.counters["splits"] = splits / steps;
  state.counters["bytes_per_tet"] = s.bytes_per_tetrahedron;
  if (!converged) state.SkipWithError("a solve missed its tolerance");
}

void Step(benchmark::State& state) {
  const auto preconditioner = static_cast<core::SolverSettings::Preconditioner>(state.range(1));
  timeSwingSteps(state, swinging(static_cast<int>(state.range(0)), preconditioner,
                                 static_cast<int>(state.range(2))));
}

void LawStep(benchmark::State& state) {
  timeSwingSteps(state, swinging(static_cast<int>(state.range(1)),
                                 core::SolverSettings::Preconditioner::kTwoLevel, 1,
                                 static_cast<core::ElasticLaw>(state.range(0))));
}

void MatVec(benchmark::State& state) {
  Swinging& s = swinging(static_cast<int>(state.range(0)),
                         core::SolverSettings::Preconditioner::kTwoLevel, 1);
  const core::BlockSparseMatrix& k = s.body->elasticity().stiffness();
  Eigen::VectorXd y(s.body->positions().size());
  for (auto _ : state) {
    k.multiply(s.body->positions(), y);
    benchmark::DoNotOptimize(y.data());
  }
  state.counters["tets"] = s.body->mesh().numTetrahedra();
  state.counters["blocks"] = k.numBlocks();
}

// Bullet steps per 0.01 s that keep btDeformableCorotatedForce stable, per mesh (see above).
const std::array<int, 2> kCorotatedForceSubsteps = {25, 44};

// One swinging peer per (mesh, force), warmed up like the core's bodies.
perf::BulletPeer& swingingPeer(int mesh, bool corotated_force) {
  static std::map<std::pair<int, bool>, std::unique_ptr<perf::BulletPeer>> peers;
  std::unique_ptr<perf::BulletPeer>& peer = peers[{mesh, corotated_force}];
  if (!peer) {
    perf::BulletPeerSettings settings;
    settings.max_newton_iterations = 1;
    if (corotated_force) {
      settings.elasticity = perf::BulletElasticity::kCorotatedForce;
      settings.substeps = kCorotatedForceSubsteps[mesh];
    }
    peer = std::make_unique<perf::BulletPeer>(perf::makeCantilever(kCells[mesh]), settings);
    for (int k = 0; k < kWarmUpSteps; ++k) peer->step();
  }
  return *peer;
}

void BulletStep(benchmark::State& state) {
  perf::BulletPeer& peer = swingingPeer(static_cast<int>(state.range(0)), state.range(1) != 0);
  double newton = 0.0;
  double iterations = 0.0;
  for (auto _ : state) {
    const perf::BulletStepReport report = peer.step();
    newton += report.newton_iterations;
    iterations += report.cg_iterations;
  }
  const double steps = static_cast<double>(state.iterations());
  state.counters["tets"] = peer.numTetrahedra();
  state.counters["bullet_steps"] = newton / steps;  // one Newton iteration per Bullet step
  state.counters["cg_iterations"] = iterations / steps;
  const Eigen::Vector3d tip = peer.position(peer.numNodes() - 1);
  if (!tip.allFinite() || tip.norm() > 10.0) state.SkipWithError("the peer blew up");
}

enum Effect {
  kNoEffect,
  kWarping,
  kGravity,
  kDamping,
  kPlasticity,
  kReactions,
  kContact,
  kStrainColouring,
  kAllEffects
};

// The cantilever with a 50 N tip load and only the effects asked for.
perf::Cantilever loadedCantilever(int mesh, Effect effect) {
  perf::Cantilever c = perf::makeCantilever(kCells[mesh]);
  const bool all = effect == kAllEffects;
  c.effects = core::BodyEffects{};
  c.effects.reactions = all || effect == kReactions || effect == kContact;  // contact needs them
  c.effects.warping = all || effect == kWarping;
  if (all || effect == kGravity) c.effects.gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
  if (all || effect == kDamping) c.effects.damping = core::RayleighDamping{1.0, 0.002};
  if (all || effect == kPlasticity)
    c.effects.plasticity = core::PlasticitySettings{1e-3, 10.0, 0.1};
  c.effects.stress_colouring = all || effect == kStrainColouring;
  return c;
}

void addTipLoad(core::Body& body) {
  std::vector<int> tip;
  for (int i = 0; i < body.numNodes(); ++i) {
    if (body.mesh().positions[i].x() > 0.6 - 1e-9) tip.push_back(i);
  }
  core::addTotalForce(tip, {0.0, 0.0, -50.0}, body.externalForces());
}

// The loaded cantilever as a one-body simulation with only `effect`; with contact, over a floor
// it sags onto.
core::Simulation effectScene(Effect effect) {
  const perf::Cantilever c = loadedCantilever(1, effect);
  core::SceneSpec spec;
  spec.dt = c.dt;
  spec.effects = c.effects;
  spec.solver = c.solver;
  if (effect == kContact || effect == kAllEffects) {
    spec.contact = core::ContactSettings{};
    core::PlacedShape floor;
    floor.name = "floor";
    floor.shape.size = Eigen::Vector3d(4.0, 4.0, 0.2);
    floor.pose.translation() = Eigen::Vector3d(0.0, 0.0, -0.21);  // top at z = -0.11
    spec.obstacles = {floor};
  }
  core::BodySpec body;
  body.name = "cantilever";
  body.material = c.material;
  spec.bodies = {body};
  core::Simulation sim(spec, {c.mesh});
  sim.bodies()[0].fixNodes(c.clamped);
  addTipLoad(sim.bodies()[0]);
  return sim;
}

void EffectCost(benchmark::State& state) {
  core::Simulation sim = effectScene(static_cast<Effect>(state.range(0)));
  const core::Body& body = sim.bodies()[0];
  std::vector<core::StepReport> reports;
  std::vector<double> strain;
  double iterations = 0.0;
  const auto step = [&] {
    sim.step(reports);
    if (body.settings().effects.stress_colouring) core::nodalStrain(body, strain);
    return reports[0];
  };
  for (int k = 0; k < kWarmUpSteps; ++k) step();
  for (auto _ : state) iterations += step().solve.iterations;
  state.counters["cg_iterations"] = iterations / static_cast<double>(state.iterations());
  state.counters["contacts"] = reports[0].contacts;
}

void ModelStep(benchmark::State& state) {
  const auto model = state.range(0) == 0 ? core::BodyModel::kRigid : core::BodyModel::kPseudoRigid;
  const int mesh = static_cast<int>(state.range(1));
  perf::Cantilever c = perf::makeCantilever(kCells[mesh]);
  core::ReducedBody body("cantilever", c.mesh, c.material, c.effects, c.solver, model);
  addTipLoad(body);
  for (auto _ : state) body.step(c.dt);
  state.counters["tets"] = body.mesh().numTetrahedra();
  benchmark::DoNotOptimize(body.reduced().centre().data());
}

void ContactCost(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0)), contact = static_cast<int>(state.range(1));
  perf::BlocksOnFloor scene{count, contact >= 1, contact >= 2};
  scene.direct = state.range(2) == 1;
  scene.threads = static_cast<int>(state.range(3));
  core::Simulation sim = perf::makeBlocksOnFloor(scene);
  std::vector<core::StepReport> reports;
  for (int k = 0; k < kWarmUpSteps; ++k) sim.step(reports);  // settled on the floor
  double pairs = 0.0, solves = 0.0;
  for (auto _ : state) {
    sim.step(reports);
    for (const core::StepReport& r : reports) {
      pairs += r.body_contacts;
      solves += r.body_contact_solves;
    }
  }
  // Each pair is counted by both of its bodies.
  state.counters["body_pairs"] = 0.5 * pairs / static_cast<double>(state.iterations());
  state.counters["solves"] = solves / static_cast<double>(state.iterations());
}

void ManyBodies(benchmark::State& state) {
  perf::BlocksOnFloor scene;
  scene.count = static_cast<int>(state.range(0));
  scene.threads = static_cast<int>(state.range(1));
  scene.floor = false;
  core::Simulation sim = perf::makeBlocksOnFloor(scene);
  std::vector<core::StepReport> reports;
  for (int k = 0; k < kWarmUpSteps; ++k) sim.step(reports);
  for (auto _ : state) sim.step(reports);
}

void VoxelizeScan(benchmark::State& state) {
  static const core::TriangleMesh blob = perf::makeScanBlob();
  core::TriangleMesh surface = blob;
  if (state.range(1) == 0) surface.triangles.pop_back();
  core::VoxelSettings settings;
  settings.longest_side_cells = static_cast<int>(state.range(0));
  std::size_t cells = 0;
  for (auto _ : state) {
    const core::Voxelization voxels =
        core::voxelize(surface, core::voxelGridFor(surface, settings), settings.levels);
    cells = voxels.mesh.cells.size();
  }
  state.counters["cells"] = static_cast<double>(cells);
  state.counters["triangles"] = static_cast<double>(surface.triangles.size());
}

void CheckScan(benchmark::State& state) {
  static const core::TriangleMesh blob = perf::makeScanBlob();
  core::SurfaceCheck check;
  for (auto _ : state) {
    core::TriangleMesh surface = blob;
    check = core::checkSurface(surface);
  }
  state.counters["triangles"] = static_cast<double>(blob.triangles.size());
  state.counters["crossings"] = static_cast<double>(check.crossings.pairs);
}

void MachineRead(benchmark::State& state) {
  const std::size_t count = static_cast<std::size_t>(state.range(0)) * 1024 / sizeof(double);
  std::vector<double> values(count, 1.0);
  for (auto _ : state) benchmark::DoNotOptimize(perf::sumArray(values.data(), count));
  state.counters["GB"] = benchmark::Counter(static_cast<double>(count * sizeof(double)) / 1e9,
                                            benchmark::Counter::kIsIterationInvariantRate);
}

void MachineFma(benchmark::State& state) {
  constexpr long kRounds = 1000000;
  for (auto _ : state) benchmark::DoNotOptimize(perf::multiplyAddChains(kRounds));
  state.counters["GFlop"] = benchmark::Counter(kRounds * perf::kFlopsPerRound / 1e9,
                                               benchmark::Counter::kIsIterationInvariantRate);
}

void meshSizes(benchmark::internal::Benchmark* b, bool with_preconditioners) {
  for (int mesh = 0; mesh < static_cast<int>(kCells.size()); ++mesh) {
    if (!with_preconditioners) {
      b->Args({mesh});
      continue;
    }
    for (int p : {1, 0, 2}) {
      if (p == 2 && mesh > 1) continue;  // its fill grows too fast for the larger meshes
      for (int threads : {1, 2}) b->Args({mesh, p, threads});
    }
  }
}

// Every run times the same 200 steps of the swing (2 s of it), whatever the speed.
BENCHMARK(Step)
    ->Apply([](benchmark::internal::Benchmark* b) { meshSizes(b, true); })
    ->ArgNames({"mesh", "preconditioner", "threads"})
    ->Iterations(kTimedSteps)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(LawStep)
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->ArgNames({"law", "mesh"})
    ->Iterations(kTimedSteps)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK(BulletStep)
    ->Args({0, 0})
    ->Args({0, 1})
    ->Args({1, 0})
    ->Args({1, 1})
    ->ArgNames({"mesh", "corotated_force"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(EffectCost)
    ->Iterations(kTimedSteps)
    ->DenseRange(kNoEffect, kAllEffects)
    ->ArgNames({"effect"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(ModelStep)
    ->Args({0, 0})
    ->Args({0, 3})
    ->Args({1, 0})
    ->Args({1, 3})
    ->ArgNames({"model", "mesh"})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK(ManyBodies)
    ->ArgsProduct({{1, 5, 20}, {1, 2}})
    ->ArgNames({"bodies", "threads"})
    ->Iterations(kTimedSteps)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK(ContactCost)
    ->Apply([](benchmark::internal::Benchmark* b) {
      for (int bodies : {1, 5, 20}) {
        for (int contact : {0, 1, 2}) {
          for (int direct : {0, 1}) b->Args({bodies, contact, direct, 1});
          if (bodies > 1 && contact < 2) b->Args({bodies, contact, 0, 2});
        }
      }
    })
    ->ArgNames({"bodies", "contact", "direct", "threads"})
    ->Iterations(20)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK(MatVec)
    ->Apply([](benchmark::internal::Benchmark* b) { meshSizes(b, false); })
    ->ArgNames({"mesh"})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();

BENCHMARK(CheckScan)->Unit(benchmark::kMillisecond);
BENCHMARK(VoxelizeScan)
    ->Args({26, 1})
    ->Args({58, 1})
    ->Args({26, 0})
    ->ArgNames({"side_cells", "closed"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// L1 (48 KiB here), L2 (1 MiB), the 9k mesh's matrix (1.9 MB) and the 98k one's (19 MB) in L3,
// and memory.
BENCHMARK(MachineRead)
    ->Arg(32)
    ->Arg(512)
    ->Arg(2048)
    ->Arg(20 * 1024)
    ->Arg(256 * 1024)
    ->ArgNames({"KiB"})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK(MachineFma)->Unit(benchmark::kMillisecond)->UseRealTime();

// BENCHMARK_MAIN with a usage of our own for --help and -h.
bool helpAsked(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) return true;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  if (helpAsked(argc, argv)) {
    std::fputs(kUsage, stdout);
    benchmark::PrintDefaultHelp();
    return 0;
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
