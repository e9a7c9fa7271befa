// deformable_sim_run: runs a scene offline (no ROS) and writes the displacement of every node.
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "deformable_sim/core/base/late_progress_bar.h"
#include "deformable_sim/core/outputs/body_activity.h"
#include "deformable_sim/io/mesh_reader.h"
#include "deformable_sim/io/scene_file.h"
#include "sleeping_openmp_threads.h"

namespace {

constexpr const char* kUsage =
    "usage: deformable_sim_run SCENE.yaml [--static | --steps N] [--out FILE.csv]\n"
    "                          [--surface-out FILE.csv] [--quiet]\n"
    "  --static     solve for equilibrium under the scene's loads (quasi-static)\n"
    "  --steps N    take N dynamic steps of the scene's dt (default 1)\n"
    "  --out FILE   write node,x0,y0,z0,ux,uy,uz per node (mesh file numbers) to FILE\n"
    "  --surface-out FILE\n"
    "               write body,vertex,x0,y0,z0,ux,uy,uz per vertex of the surfaces that bodies\n"
    "               were made from (mesh: {surface: ..}); vertices numbered from 1 in the\n"
    "               file's order, an STL's repeated vertices once\n"
    "  --quiet      print only the summary (bodies, mean time per step, energies), not every\n"
    "               step\n"
    "Robot links (urdf.links) are not simulated offline: give them as obstacles instead.\n"
    "  --help, -h   print this usage and exit\n";

struct Options {
  std::string scene;
  bool quasi_static = false;
  long steps = 1;
  std::string out;
  std::string surface_out;
  bool quiet = false;
};

enum class Parsed { kRun, kHelp, kBad };

Parsed parseArguments(int argc, char** argv, Options& options) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") return Parsed::kHelp;
    if (arg == "--static") {
      options.quasi_static = true;
    } else if (arg == "--steps" && i + 1 < argc) {
      char* end = nullptr;
      options.steps = std::strtol(argv[++i], &end, 10);
      if (*end != '\0' || options.steps < 0) return Parsed::kBad;
    } else if (arg == "--out" && i + 1 < argc) {
      options.out = argv[++i];
    } else if (arg == "--surface-out" && i + 1 < argc) {
      options.surface_out = argv[++i];
    } else if (arg == "--quiet") {
      options.quiet = true;
    } else if (!arg.empty() && arg[0] != '-' && options.scene.empty()) {
      options.scene = arg;
    } else {
      return Parsed::kBad;
    }
  }
  return options.scene.empty() ? Parsed::kBad : Parsed::kRun;
}

void writeDisplacements(const deformable_sim::core::Simulation& sim, std::ostream& out) {
  const bool several = sim.bodies().size() > 1;
  out << (several ? "body," : "") << "node,x0,y0,z0,ux,uy,uz\n";
  out.precision(17);
  for (const auto& body : sim.bodies()) {
    const Eigen::VectorXd u = body.positions() - body.restPositions();
    for (int i = 0; i < body.numNodes(); ++i) {
      if (several) out << body.name() << ",";
      out << body.mesh().node_numbers[i];
      for (int c = 0; c < 3; ++c) out << "," << body.restPositions()[3 * i + c];
      for (int c = 0; c < 3; ++c) out << "," << u[3 * i + c];
      out << "\n";
    }
  }
}

// The embedded surfaces, moved to the bodies' positions: one row per vertex.
void writeSurfaceDisplacements(deformable_sim::core::Simulation& sim, std::ostream& out) {
  out << "body,vertex,x0,y0,z0,ux,uy,uz\n";
  out.precision(17);
  for (int b = 0; b < static_cast<int>(sim.bodies().size()); ++b) {
    deformable_sim::core::EmbeddedSurface* surface = sim.embeddedSurface(b);
    if (!surface) continue;
    surface->update(sim.bodies()[b].positions());
    for (int v = 0; v < surface->numVertices(); ++v) {
      const Eigen::Vector3d& x0 = surface->restPositions()[v];
      const Eigen::Vector3d u = surface->positions()[v] - x0;
      out << sim.bodies()[b].name() << "," << v + 1;
      for (int c = 0; c < 3; ++c) out << "," << x0[c];
      for (int c = 0; c < 3; ++c) out << "," << u[c];
      out << "\n";
    }
  }
}

Eigen::Vector3d sumOfReactions(const deformable_sim::core::Body& body) {
  return body.reactionForces().reshaped(3, body.numNodes()).rowwise().sum();
}

using deformable_sim::core::Simulation;
using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void printBodies(const Simulation& sim) {
  for (size_t b = 0; b < sim.bodies().size(); ++b) {
    std::printf("%s\n", deformable_sim::core::bodySummary(sim, static_cast<int>(b)).c_str());
  }
}

// Solves for equilibrium and prints each body's report; true when every body converged.
bool solveStatic(Simulation& sim) {
  bool converged = true;
  const auto start = Clock::now();
  const auto reports = sim.solveStatic();
  const double ms = millisecondsSince(start);
  for (size_t b = 0; b < reports.size(); ++b) {
    const auto& r = reports[b];
    const Eigen::Vector3d reaction = sumOfReactions(sim.bodies()[b]);
    std::printf(
        "static %s: %s in %.1f ms, %d corotational iterations, %d CG iterations, last change "
        "%.3g, residual %.3g; reactions sum to (%.9g, %.9g, %.9g) N\n",
        sim.bodies()[b].name().c_str(), r.converged ? "converged" : "NOT converged", ms,
        r.iterations, r.linear_iterations, r.last_change, r.last_solve.relative_residual,
        reaction.x(), reaction.y(), reaction.z());
    converged = converged && r.converged;
  }
  return converged;
}

// The contacts of a body's step, if it had any: with obstacles, other bodies and itself.
void printContacts(const deformable_sim::core::StepReport& r) {
  if (r.contacts > 0) std::printf(", %d on obstacles", r.contacts);
  if (r.body_contacts > 0) {
    std::printf(", %d with bodies (left %.3g m deep)", r.body_contacts, r.body_penetration);
  }
  if (r.self_contacts > 0) std::printf(", %d with itself", r.self_contacts);
}

// Each body's linear solves a step: for a Neo-Hookean body, its Newton iterations.
void printSolvesPerStep(const Simulation& sim, const std::vector<long>& solves, long steps) {
  for (size_t b = 0; b < solves.size(); ++b) {
    const deformable_sim::core::Body& body = sim.bodies()[b];
    const bool newton =
        body.settings().material.law == deformable_sim::core::ElasticLaw::kNeoHookean;
    std::printf("%s: %.2f %s per step (mean)\n", body.name().c_str(),
                static_cast<double>(solves[b]) / static_cast<double>(steps),
                newton ? "Newton iterations" : "solves");
  }
}

// Takes the steps and prints each (unless quiet), then the mean time per step and the energies;
// true when every solve converged.
bool stepDynamically(Simulation& sim, const Options& options) {
  bool converged = true;
  std::vector<deformable_sim::core::StepReport> reports;
  std::vector<long> solves(sim.bodies().size(), 0);
  double total_ms = 0.0;
  for (long s = 0; s < options.steps; ++s) {
    const auto start = Clock::now();
    sim.step(reports);
    const double ms = millisecondsSince(start);
    total_ms += ms;
    for (size_t b = 0; b < reports.size(); ++b) {
      converged = converged && reports[b].solve.converged;
      solves[b] += reports[b].solves;
      if (options.quiet) continue;
      std::printf("step %ld t=%.6g s %s: %.3f ms, %d iterations, residual %.3g%s", sim.stepCount(),
                  sim.time(), sim.bodies()[b].name().c_str(), ms, reports[b].solve.iterations,
                  reports[b].solve.relative_residual,
                  reports[b].inverted_elements ? ", inverted elements" : "");
      if (reports[b].solves > 1) std::printf(", %d solves", reports[b].solves);
      if (reports[b].splits > 0) std::printf(", %d splits", reports[b].splits);
      printContacts(reports[b]);
      std::printf("\n");
    }
  }
  if (options.steps > 0) {
    std::printf("%ld steps in %.1f ms: %.3f ms per step (mean)\n", options.steps, total_ms,
                total_ms / static_cast<double>(options.steps));
    printSolvesPerStep(sim, solves, options.steps);
  }
  for (const auto& body : sim.bodies()) {
    std::printf("after %ld steps %s: kinetic %.6g J, elastic %.6g J\n", sim.stepCount(),
                body.name().c_str(), body.kineticEnergy(), body.elasticEnergy());
  }
  return converged;
}

// Where surfaces are voxelized, a bar on stderr for each body that takes more than a second.
deformable_sim::io::SurfaceSources surfaceProgress() {
  deformable_sim::io::SurfaceSources sources;
  auto bar = std::make_shared<std::optional<deformable_sim::core::LateProgressBar>>();
  sources.progress = [bar](const std::string& body, long done, long total) {
    if (done == 0 || !bar->has_value())
      bar->emplace(stderr, "grid cells of body '" + body + "' voxelized");
    (*bar)->update(done, total, "body '" + body + "'");
    if (done == total) (*bar)->finish();
  };
  return sources;
}

// The scene's robot links move with tf in the node; offline nothing places them, so they are left
// out, and the user is told so.
void warnAboutRobotLinks(const deformable_sim::core::SceneSpec& spec) {
  if (spec.urdf_links.empty()) return;
  std::string names;
  for (const std::string& link : spec.urdf_links) names += (names.empty() ? "" : ", ") + link;
  std::cerr << "warning: urdf.links (" << names
            << "): robot links are not simulated offline; give them as obstacles\n";
}

// Runs the scene as the options say; the process's exit status.
int run(const Options& options) {
  std::vector<std::string> warnings;
  const deformable_sim::core::SceneSpec spec = deformable_sim::io::readSceneFile(options.scene);
  warnAboutRobotLinks(spec);
  Simulation sim = deformable_sim::io::buildSimulation(spec, &warnings, surfaceProgress());
  for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
  printBodies(sim);
  const bool converged = options.quasi_static ? solveStatic(sim) : stepDynamically(sim, options);
  if (!options.out.empty()) {
    std::ofstream out(options.out);
    if (!out) throw std::runtime_error(options.out + ": cannot write");
    writeDisplacements(sim, out);
  }
  if (!options.surface_out.empty()) {
    std::ofstream out(options.surface_out);
    if (!out) throw std::runtime_error(options.surface_out + ": cannot write");
    writeSurfaceDisplacements(sim, out);
  }
  if (!converged) {
    std::fprintf(stderr, "warning: a solve did not reach its tolerance\n");
    return 3;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  deformable_sim::letOpenMpThreadsSleep(argv);
  Options options;
  switch (parseArguments(argc, argv, options)) {
    case Parsed::kHelp:
      std::cout << kUsage;
      return 0;
    case Parsed::kBad:
      std::cerr << kUsage;
      return 2;
    case Parsed::kRun:
      break;
  }
  try {
    return run(options);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
