#include "deformable_sim/bench/static_cases.h"

#include <chrono>
#include <cmath>
#include <sstream>

#include "deformable_sim/bench/heap_usage.h"

namespace deformable_sim::bench {

namespace {

constexpr double kCaseALoad = 0.025;  // N
// The converged 3D solution: CalculiX C3D20R on hex20_L4 (the reference README, section 4).
constexpr const char* kConvergedElement = "C3D20R";

// CalculiX's element on the same mesh: full-integration C3D8 on the hexahedral meshes, C3D4 else.
std::string sameMeshElement(const std::string& mesh) {
  return mesh.rfind("hex_", 0) == 0 ? "C3D8" : "C3D4";
}
constexpr const char* kConvergedMesh = "hex20_L4";

// CalculiX ran on the shipped meshes only: a beam made from its surface has no same-mesh value.
bool hasSameMeshResults(const std::string& mesh) {
  double turn = 0.0;
  int cells = 0;
  return !ReferenceBeam::parseSurfaceId(mesh, &turn, &cells);
}

// Solves the body statically with the tip load applied, timing the whole solve.
void solveTimed(core::Body& body, const core::StaticSettings& statics, CaseRun& run) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const core::StaticReport report = body.solveStatic(statics);
  run.step_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
  run.linear_solves += report.iterations;
  run.cg_iterations += report.linear_iterations;
  run.converged = run.converged && report.converged;
}

// The setting's beam solved statically under a tip load of `load` N: the solve timed, the
// memory of the body measured.
core::FiniteElementBody solveUnderTipLoad(const BenchSetting& setting, const ReferenceBeam& beam,
                                          double load, const core::StaticSettings& statics,
                                          CaseRun& run) {
  core::BodyEffects effects;
  effects.warping = setting.warping;
  const std::size_t heap_before = liveHeapBytes();
  core::FiniteElementBody body = beam.makeBeamBody(effects, setting.solver);
  beam.applyTipLoad(body, load);
  solveTimed(body, statics, run);
  run.memory_bytes = liveHeapBytes() - heap_before;
  return body;
}

std::string alphaParam(double alpha) {
  std::ostringstream text;
  text << "alpha=" << alpha << " (";  // "alpha=1 (P=8.33333 N)", not "alpha=1.5 (..."
  return text.str();
}

}  // namespace

CaseRun runLinearStatic(const BenchSetting& setting, BenchContext& context) {
  const ReferenceBeam& beam = context.beam(setting.mesh);
  const ReferenceResults& results = context.results();
  CaseRun run;
  // One load step, change below 1e-8.
  const core::FiniteElementBody body =
      solveUnderTipLoad(setting, beam, kCaseALoad, core::StaticSettings{}, run);

  Comparison tip;
  tip.case_name = "A_static";
  tip.value = beam.tipDisplacement(body).z();
  tip.reference_value =
      results.value("A", kConvergedElement, kConvergedMesh, "", "tip_uz_mean_area");
  tip.same_mesh_value =
      hasSameMeshResults(setting.mesh)
          ? results.value("A", sameMeshElement(setting.mesh), setting.mesh, "", "tip_uz_mean_area")
          : NAN;
  tip.theory_value = results.value("A", "analytical", "", "", "tip_uz_Timoshenko");
  tip.error = std::abs(tip.value / tip.reference_value - 1.0);
  tip.error_same_mesh = std::abs(tip.value / tip.same_mesh_value - 1.0);
  tip.error_definition =
      "|uz/uz_ref - 1| of the tip face's area-mean uz under P = 0.025 N (a surface's grid: the "
      "mean of its tip nodes); ref: converged 3D (hex20_L4 C3D20R); same mesh: CalculiX C3D4 "
      "(C3D8 on hex meshes)";
  run.comparisons.push_back(tip);
  return run;
}

CaseRun runLargeDeflection(const BenchSetting& setting, BenchContext& context) {
  const ReferenceBeam& beam = context.beam(setting.mesh);
  const ReferenceResults& results = context.results();
  CaseRun run;
  const core::FiniteElementBody body = solveUnderTipLoad(
      setting, beam, largeDeflectionLoad(setting.alpha), core::StaticSettings{4, 500, 1e-9}, run);

  const std::string param = alphaParam(setting.alpha);
  auto tipOf = [&](const std::string& element, const std::string& mesh) {
    return Eigen::Vector2d(results.value("B", element, mesh, param, "tip_ux_mean_area"),
                           results.value("B", element, mesh, param, "tip_uz_mean_area"));
  };
  const Eigen::Vector3d u = beam.tipDisplacement(body);
  const Eigen::Vector2d tip(u.x(), u.z());
  const Eigen::Vector2d converged = tipOf(kConvergedElement, kConvergedMesh);
  const Eigen::Vector2d same_mesh = hasSameMeshResults(setting.mesh)
                                        ? tipOf(sameMeshElement(setting.mesh), setting.mesh)
                                        : Eigen::Vector2d(NAN, NAN);

  Comparison c;
  std::ostringstream name;
  name << "B_alpha" << setting.alpha;
  c.case_name = name.str();
  c.value = tip.y();
  c.reference_value = converged.y();
  c.same_mesh_value = same_mesh.y();
  c.theory_value = results.value("B", "analytical", "", param, "tip_uz_elastica");
  c.error = (tip - converged).norm() / converged.norm();
  c.error_same_mesh = (tip - same_mesh).norm() / same_mesh.norm();
  c.error_definition =
      "|u - u_ref| / |u_ref| of the tip face's area-mean (ux, uz) under P = alpha EI/L^2; value: "
      "uz; ref: converged 3D (hex20_L4 C3D20R NLGEOM); same mesh: CalculiX C3D4 (C3D8 on hex "
      "meshes) NLGEOM";
  run.comparisons.push_back(c);
  return run;
}

}  // namespace deformable_sim::bench
