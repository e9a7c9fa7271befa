#include "deformable_sim/ros/replay.h"

#include <chrono>

#include "deformable_sim/core/outputs/body_colours.h"
#include "deformable_sim/io/scene_file.h"
#include "deformable_sim/io/triangle_mesh_reader.h"
#include "deformable_sim/ros/obstacle_mesh_messages.h"
#include "deformable_sim/ros/recorded_session.h"
#include "deformable_sim/ros/resimulated_bag.h"
#include "deformable_sim/ros/session_messages.h"

namespace deformable_sim::ros_layer {

namespace {

// The mesh obstacles' triangles as ~scene recorded them, in place of their files.
io::ObstacleMeshLoader recordedMeshes(const Scene& scene) {
  return [&scene](const std::string& key, const std::string& path, const Eigen::Vector3d&) {
    for (const ObstacleMesh& mesh : scene.obstacle_meshes) {
      if (mesh.id != key) continue;
      try {
        return fromMessage(mesh);
      } catch (const core::CommandError& e) {
        throw io::TriangleMeshError(e.what());
      }
    }
    throw io::TriangleMeshError("mesh file '" + path +
                                "': the recorded scene has no triangles for " + key);
  };
}

}  // namespace

core::SceneSpec recordedSceneSpec(const Scene& scene) {
  core::SceneSpec spec;
  try {
    spec = io::sceneFromFileText(scene.yaml, scene.path, recordedMeshes(scene));
  } catch (const io::SceneError& e) {
    throw ReplayError(std::string("the recorded scene: ") + e.what());
  }
  spec.dt = scene.dt;
  return spec;
}

namespace {

core::SolverSettings::Method solverMethod(const std::string& name) {
  if (name == "cg") return core::SolverSettings::Method::kConjugateGradient;
  if (name == "direct") return core::SolverSettings::Method::kDirect;
  throw ReplayError("--solver: '" + name + "' is neither cg nor direct");
}

}  // namespace

Replay::Replay(ReplayOptions options)
    : options_(std::move(options)),
      recorded_(
          std::make_unique<RecordedSession>(readRecordedSession(options_.input, options_.node))) {
  std::vector<core::Mesh> meshes;
  std::vector<std::optional<core::EmbeddedSurface>> surfaces;
  try {
    meshes = meshesFromMessage(recorded_->scene, &surfaces);
  } catch (const std::invalid_argument& e) {
    throw ReplayError(e.what());
  }
  const core::SolverOverride solver{options_.solver_tolerance, options_.solver_max_iterations};
  try {
    resimulation_ = std::make_unique<core::Resimulation>(sceneSpec(), std::move(meshes),
                                                         std::move(recorded_->recording), solver,
                                                         std::move(surfaces));
  } catch (const core::ResimulationError& e) {
    throw ReplayError(options_.input + ": " + e.what());
  } catch (const std::invalid_argument& e) {
    throw ReplayError(std::string("the recorded scene: ") + e.what());
  }
}

Replay::~Replay() = default;

core::SceneSpec Replay::sceneSpec() const {
  core::SceneSpec spec = recordedSceneSpec(recorded_->scene);
  if (options_.solver_method) spec.solver.method = solverMethod(*options_.solver_method);
  if (options_.threads) spec.solver.threads = *options_.threads;
  // The bodies are built with these too; the re-simulation keeps them through resets and tuning.
  if (options_.solver_tolerance) spec.solver.tolerance = *options_.solver_tolerance;
  if (options_.solver_max_iterations) spec.solver.max_iterations = *options_.solver_max_iterations;
  return spec;
}

ReplayReport Replay::run(std::FILE* progress) {
  ReplayReport report;
  report.node = recorded_->node;
  report.threads = resimulation_->session().scene().solver.threads;
  const auto start = std::chrono::steady_clock::now();
  report.resimulation = resimulate(progress);
  report.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // What this build cannot read it cannot apply: refused, as the node would have.
  report.resimulation.refused_commands += recorded_->unknown_commands;
  return report;
}

core::ResimulationReport Replay::resimulate(std::FILE* progress) {
  std::unique_ptr<ResimulatedBag> out;
  if (!options_.output.empty()) {
    out = std::make_unique<ResimulatedBag>(
        options_.output, recorded_->node, recorded_->scene, resimulation_->session().simulation(),
        recorded_->state_headers, options_.marker_rate, core::bodyColours(sceneSpec()));
  }
  std::optional<core::ProgressBar> bar;
  if (progress) bar.emplace(resimulation_->plannedSteps(), progress, "steps");
  const core::Resimulation::Observer write = [&out](const core::ComparedState& state) {
    out->write(state);
  };
  core::ResimulationReport report;
  try {
    report =
        resimulation_->run(out ? write : core::Resimulation::Observer(), bar ? &*bar : nullptr);
  } catch (const core::ResimulationError& e) {
    throw ReplayError(options_.input + ": " + e.what());
  }
  if (bar) bar->finish();
  if (out) out->close();
  return report;
}

}  // namespace deformable_sim::ros_layer
