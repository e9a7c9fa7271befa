#include "deformable_sim/bench/sweep_plan.h"

#include <algorithm>
#include <stdexcept>

namespace deformable_sim::bench {

namespace {

using Method = core::SolverSettings::Method;

constexpr int kUncapped = 100000;  // far above what any mesh here needs

core::SolverSettings direct() {
  core::SolverSettings s;
  s.method = Method::kDirect;
  return s;
}

core::SolverSettings cg(double tolerance, int max_iterations = kUncapped) {
  core::SolverSettings s;
  s.method = Method::kConjugateGradient;
  s.tolerance = tolerance;
  s.max_iterations = max_iterations;
  return s;
}

BenchSetting make(CaseKind kind, const std::string& mesh, bool warping,
                  const core::SolverSettings& solver, double dt = 0.0, int substeps = 1) {
  BenchSetting s;
  s.kind = kind;
  s.mesh = mesh;
  s.warping = warping;
  s.solver = solver;
  s.dt_s = dt;
  s.substeps = substeps;
  return s;
}

// The knobs of one dynamic case on one mesh. Rates are 1/dt in Hz; tolerances, caps and
// substeps are tried at one rate each (see below).
struct DynamicKnobs {
  std::string mesh;
  std::vector<int> warped_direct_rates;
  std::vector<int> linear_direct_rates;
  std::vector<double> tolerances;         // warped CG at 60 Hz
  std::vector<int> caps;                  // warped CG at 60 Hz, tolerance 1e-8
  std::vector<int> substeps;              // warped direct at 30 Hz
  std::vector<int> warped_cg_rates = {};  // warped CG, tolerance 1e-4 (where direct is too slow)
};

void addDynamic(CaseKind kind, const DynamicKnobs& k, std::vector<BenchSetting>& plan) {
  for (int rate : k.warped_direct_rates)
    plan.push_back(make(kind, k.mesh, true, direct(), 1.0 / rate));
  for (int rate : k.linear_direct_rates)
    plan.push_back(make(kind, k.mesh, false, direct(), 1.0 / rate));
  for (int rate : k.warped_cg_rates) plan.push_back(make(kind, k.mesh, true, cg(1e-4), 1.0 / rate));
  for (double t : k.tolerances) plan.push_back(make(kind, k.mesh, true, cg(t), 1.0 / 60));
  for (int cap : k.caps) plan.push_back(make(kind, k.mesh, true, cg(1e-8, cap), 1.0 / 60));
  for (int n : k.substeps) plan.push_back(make(kind, k.mesh, true, direct(), 1.0 / 30, n));
}

// A: discretisation error (direct), the cost of warping where it changes nothing, CG's tolerance
// and iteration cap. B: warping against linear FEM at large rotations.
void addStatic(const std::vector<std::string>& meshes, const std::vector<std::string>& b_meshes,
               const std::vector<double>& tolerances, const std::string& cap_mesh,
               const std::vector<int>& caps, bool full, std::vector<BenchSetting>& plan) {
  for (const std::string& mesh : meshes) {
    plan.push_back(make(CaseKind::kLinearStatic, mesh, false, direct()));
    if (full) plan.push_back(make(CaseKind::kLinearStatic, mesh, true, direct()));
    for (double t : tolerances) plan.push_back(make(CaseKind::kLinearStatic, mesh, false, cg(t)));
  }
  for (int cap : caps)
    plan.push_back(make(CaseKind::kLinearStatic, cap_mesh, false, cg(1e-10, cap)));
  for (double alpha : {1.0, 2.0}) {
    for (const std::string& mesh : b_meshes) {
      std::vector<BenchSetting> variants = {
          make(CaseKind::kLargeDeflection, mesh, true, direct()),
          make(CaseKind::kLargeDeflection, mesh, false, direct())};
      if (full) variants.push_back(make(CaseKind::kLargeDeflection, mesh, true, cg(1e-8)));
      for (BenchSetting& s : variants) {
        s.alpha = alpha;
        plan.push_back(s);
      }
    }
  }
}

std::vector<BenchSetting> shortPlan() {
  std::vector<BenchSetting> plan;
  addStatic({"tetU_L1", "tetU_L2", "tetS_L1", "tetS_L2"},
            {"tetU_L1", "tetU_L2", "tetS_L1", "tetS_L2"}, {}, "tetU_L2", {10, 30, 100}, false,
            plan);
  for (const std::string mesh : {"tetU_L1", "tetU_L2"}) {
    for (double t : {1e-1, 1e-2, 1e-4, 1e-8})
      plan.push_back(make(CaseKind::kLinearStatic, mesh, false, cg(t)));
  }
  for (const std::string mesh : {"tetU_L1", "tetU_L2"}) {
    addDynamic(CaseKind::kFreeVibration,
               {mesh, {30, 60, 120, 240, 480}, {60}, {1e-2, 1e-4, 1e-6}, {}, {2}}, plan);
  }
  // With a warm start from the extrapolated velocity 1e-2 is already close to converged: the
  // sweep starts at 1e-1 so that the loose end shows.
  addDynamic(CaseKind::kTrajectory,
             {"tetU_L1", {30, 60, 120, 240}, {60}, {1e-1, 1e-2, 1e-4, 1e-6}, {}, {2}}, plan);
  // A beam made from its surface, along the grid (one cell across: hex_L1's nodes and elements)
  // and turned against it.
  for (const char* mesh : {"hex_L1", "surface0_c10", "surface30_c12"})
    plan.push_back(make(CaseKind::kLinearStatic, mesh, false, direct()));
  return plan;
}

std::vector<BenchSetting> fullPlan() {
  std::vector<BenchSetting> plan;
  addStatic({"tetU_L1", "tetU_L2", "tetU_L3", "tetU_L4", "tetS_L1", "tetS_L2", "tetS_L3", "tetS_L4",
             "hex_L1", "hex_L2", "hex_L3", "hex_L4"},
            // tetS_L4 takes minutes at large deflection and adds nothing tetU_L4 does not show
            {"tetU_L1", "tetU_L2", "tetU_L3", "tetU_L4", "tetS_L1", "tetS_L2", "tetS_L3", "hex_L1",
             "hex_L2", "hex_L3", "hex_L4"},
            {1e-1, 1e-2, 1e-3, 1e-4, 1e-6, 1e-8, 1e-10}, "tetU_L3", {10, 30, 100, 300, 1000}, true,
            plan);
  // The beam given as a surface, along the grid and turned 30 degrees about its axis: A at
  // several cell counts, B where the grid is fine enough to bend.
  std::vector<std::string> surfaces, b_surfaces;
  for (const char* turn : {"surface0", "surface30"}) {
    for (int cells : {12, 18, 24, 36, 48})
      surfaces.push_back(turn + std::string("_c") + std::to_string(cells));
    b_surfaces.push_back(turn + std::string("_c24"));
  }
  addStatic(surfaces, b_surfaces, {}, "", {}, true, plan);
  const std::vector<double> tolerances = {1e-1, 1e-2, 1e-3, 1e-4, 1e-6, 1e-8};
  // C2 on tetU only: the split first-mode pair of the tetS meshes beats. On tetU_L4 a warped
  // direct step refactorises 26k tetrahedra, far too slow a step: linear FEM (factorised once)
  // and CG there.
  for (const std::string mesh : {"tetU_L1", "tetU_L2"}) {
    addDynamic(CaseKind::kFreeVibration,
               {mesh, {15, 30, 60, 120, 240, 480, 960}, {60}, tolerances, {}, {2, 4, 8}}, plan);
  }
  addDynamic(CaseKind::kFreeVibration,
             {"tetU_L3", {15, 30, 60, 120}, {60}, {1e-2, 1e-4, 1e-6}, {}, {2}}, plan);
  addDynamic(CaseKind::kFreeVibration, {"tetU_L4", {}, {30, 60, 120}, {}, {}, {}, {30}}, plan);
  // T up to level 3: its converged reference (2880 warped direct steps) would take most of an
  // hour on tetU_L4.
  for (const std::string mesh : {"tetU_L1", "tetU_L2", "tetS_L2"}) {
    addDynamic(CaseKind::kTrajectory,
               {mesh, {30, 60, 120, 240, 480}, {60}, tolerances, {2, 5, 10, 20}, {2, 4, 8}}, plan);
  }
  addDynamic(CaseKind::kTrajectory,
             {"tetU_L3", {30, 60, 120, 240}, {60}, {1e-2, 1e-4, 1e-6}, {5, 20}, {2}}, plan);
  return plan;
}

}  // namespace

std::vector<BenchSetting> planSweep(SweepSize size) {
  return size == SweepSize::kShort ? shortPlan() : fullPlan();
}

std::vector<BenchSetting> selectCases(const std::vector<BenchSetting>& settings,
                                      const std::vector<std::string>& cases) {
  auto letter = [](CaseKind kind) -> std::string {
    switch (kind) {
      case CaseKind::kLinearStatic:
        return "A";
      case CaseKind::kLargeDeflection:
        return "B";
      case CaseKind::kFreeVibration:
        return "C2";
      case CaseKind::kTrajectory:
        break;
    }
    return "T";
  };
  for (const std::string& c : cases) {
    if (c != "A" && c != "B" && c != "C2" && c != "T") {
      throw std::invalid_argument("unknown case '" + c + "' (A, B, C2, T)");
    }
  }
  std::vector<BenchSetting> selected;
  for (const BenchSetting& s : settings) {
    if (std::find(cases.begin(), cases.end(), letter(s.kind)) != cases.end()) selected.push_back(s);
  }
  return selected;
}

}  // namespace deformable_sim::bench
