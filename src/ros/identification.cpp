#include "deformable_sim/ros/identification.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <fstream>

#include "deformable_sim/identify/fit_plot.h"
#include "deformable_sim/identify/fitted_scene.h"
#include "deformable_sim/identify/scene_parameter.h"
#include "deformable_sim/io/scene_file.h"
#include "deformable_sim/ros/fit_checks.h"
#include "deformable_sim/ros/measured_bag.h"
#include "deformable_sim/ros/recorded_session.h"
#include "deformable_sim/ros/replay.h"
#include "deformable_sim/ros/session_messages.h"

namespace deformable_sim::ros_layer {

namespace {

using identify::FitSpecError;

struct LoadedScene {
  core::SceneSpec spec;
  std::vector<core::Mesh> meshes;
  std::vector<std::optional<core::EmbeddedSurface>> surfaces;
  std::string yaml;  ///< the scene file's text, for `out`
};

LoadedScene loadScene(const identify::FitSpec& fit, const RecordedSession& session) {
  LoadedScene scene;
  if (fit.scene.empty()) {
    // `out` is the scene file with the fitted values: the built-in scene has no file.
    if (session.scene.yaml.empty())
      throw FitSpecError("scene: the bag's ~scene is the built-in scene: give its file as scene");
    scene.spec = recordedSceneSpec(session.scene);
    scene.meshes = meshesFromMessage(session.scene, &scene.surfaces);
    scene.yaml = session.scene.yaml;
    return scene;
  }
  try {
    scene.spec = io::readSceneFile(fit.scene);
    std::vector<std::string> warnings;
    scene.meshes = io::readMeshes(scene.spec, &warnings, &scene.surfaces);
    scene.yaml = io::readSceneText(fit.scene);
  } catch (const std::exception& e) {
    throw FitSpecError(std::string("scene: ") + e.what());
  }
  return scene;
}

// The measured episode's clock: its commands, each stamped at the instant it took effect
// (after `step` steps), and its states, at the instants they show.
identify::SessionClock sessionClock(const RecordedSession& session, double dt) {
  const long episode = identify::measuredEpisode(session.recording);
  identify::SessionClock clock;
  for (const AppliedStamp& a : session.applied_stamps) {
    if (a.episode == episode)
      clock.add(static_cast<int64_t>(a.header.stamp.toNSec()), static_cast<double>(a.step) * dt);
  }
  if (clock.empty()) throw FitSpecError("bag: the recorded log has no command to time it by");
  std::optional<int64_t> last_state;
  for (const auto& [key, state] : session.recording.states) {
    const auto& [state_episode, step, body] = key;
    if (state_episode != episode) continue;
    const auto stamp = static_cast<int64_t>(session.state_headers[state.source].stamp.toNSec());
    clock.add(stamp, static_cast<double>(step) * dt);
    last_state = std::max(last_state.value_or(stamp), stamp);
  }
  if (last_state) clock.endAt(*last_state);  // the node recorded no further
  return clock;
}

/// `outside`: per observation, the samples outside the recorded session, left out.
identify::RecordedExperiment loadExperiment(const identify::FitSpec& fit, std::string& yaml,
                                            std::vector<long>& outside) {
  RecordedSession session;
  try {
    session = readRecordedSession(fit.bag, "", fit.scene.empty());
  } catch (const ReplayError& e) {
    throw FitSpecError(std::string("bag: ") + e.what());
  }
  if (session.applied_stamps.empty()) {
    throw FitSpecError("bag: " + fit.bag + " has no ~applied message: record the node's ~applied");
  }
  LoadedScene scene = loadScene(fit, session);
  if (!fit.scene.empty()) checkSceneIsTheBags(session, scene.spec, scene.meshes);
  checkSourcesAppear(fit, session.recording, scene.spec);
  yaml = scene.yaml;
  const std::string& world = session.applied_stamps.front().header.frame_id;
  const identify::SessionClock clock = sessionClock(session, scene.spec.dt);
  Measurements measured = readMeasurements(fit.bag, fit.observations, world, clock);
  outside = measured.outside;
  identify::RecordedExperiment experiment{
      std::move(scene.spec),        std::move(scene.meshes), std::move(scene.surfaces),
      std::move(session.recording), fit.observations,        std::move(measured.sensor_frames),
      std::move(measured.series)};
  experiment.recording.states.clear();  // the fit compares measurements, not recorded states
  return experiment;
}

std::string valuesText(const std::vector<identify::FitParameter>& parameters,
                       const std::vector<double>& values) {
  std::string text;
  char buffer[160];
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::snprintf(buffer, sizeof buffer, "  %s.%s %.6g", parameters[i].body.c_str(),
                  parameters[i].parameter.c_str(), values[i]);
    text += buffer;
  }
  return text;
}

void printRms(std::FILE* out, const identify::FitSpec& fit,
              const std::vector<identify::ObservationRms>& before,
              const std::vector<identify::ObservationRms>& after) {
  for (std::size_t o = 0; o < fit.observations.size(); ++o) {
    const identify::ObservationSpec& spec = fit.observations[o];
    if (spec.kind == identify::ObservationSpec::Kind::kFrame) {
      std::fprintf(out, "RMS residual %s (tf %s): %.4g m before, %.4g m after\n", spec.key.c_str(),
                   spec.topic.c_str(), before[o].first, after[o].first);
    } else {
      std::fprintf(out,
                   "RMS residual %s (wrench %s): %.4g N %.4g N m before, %.4g N %.4g N m after\n",
                   spec.key.c_str(), spec.topic.c_str(), before[o].first, before[o].second,
                   after[o].first, after[o].second);
    }
  }
}

void printOutside(std::FILE* out, const identify::FitSpec& fit, const std::vector<long>& outside) {
  for (std::size_t o = 0; o < outside.size(); ++o) {
    if (outside[o] == 0) continue;
    std::fprintf(out, "%s (%s): %ld samples outside the recorded session left out\n",
                 fit.observations[o].key.c_str(), fit.observations[o].topic.c_str(), outside[o]);
  }
}

/// "beam.youngs_modulus", or "observations[1].time_offset".
std::string parameterName(const identify::FitParameter& p) {
  return p.observation >= 0 ? p.key : p.body + "." + p.parameter;
}

void printFitted(std::FILE* out, const identify::FitSpec& fit, const identify::FitResult& result) {
  for (std::size_t i = 0; i < fit.fit.size(); ++i) {
    const identify::FitParameter& p = fit.fit[i];
    if (p.observation >= 0) {
      std::fprintf(out, "fitted %s %.6g s ± %.3g\n", p.key.c_str(), result.values[i],
                   result.standard_deviations[i]);
    } else {
      std::fprintf(out, "fitted %s %s %.6g ± %.3g\n", p.body.c_str(), p.parameter.c_str(),
                   result.values[i], result.standard_deviations[i]);
    }
  }
  if (result.sigma_scale > 1.0) {
    std::fprintf(out,
                 "  (± scaled by the weighted RMS residual %.3g: the residuals scatter more than "
                 "their sigmas say)\n",
                 result.sigma_scale);
  }
  for (std::size_t i = 0; i < fit.fit.size(); ++i) {
    for (std::size_t j = i + 1; j < fit.fit.size(); ++j) {
      if (result.no_effect[i] || result.no_effect[j]) continue;
      std::fprintf(out, "correlation %s %s %.3f\n", parameterName(fit.fit[i]).c_str(),
                   parameterName(fit.fit[j]).c_str(), result.correlations(i, j));
    }
  }
}

/// Why the fit cannot be trusted, one reason a line; empty when it can.
std::string distrust(const identify::FitSpec& fit, const identify::FitResult& result,
                     double weighted_rms) {
  constexpr double kFarAbove = 3.0;  // weighted RMS: noise 3x the sigmas, or a wrong model
  std::string reasons;
  for (std::size_t i = 0; i < fit.fit.size(); ++i) {
    const std::string name = parameterName(fit.fit[i]);
    if (result.no_effect[i]) {
      reasons += "  " + name + " has no effect on the data (the residuals do not change with " +
                 "it): leave it out, or measure what it changes\n";
    } else if (result.at_bound[i]) {
      reasons += "  " + name + " ended at a bound of its range: widen [min, max] or check the " +
                 "scene and the data\n";
    }
  }
  if (weighted_rms > kFarAbove) {
    char line[200];
    std::snprintf(line, sizeof line,
                  "  the weighted RMS residual %.3g is far above 1: sigmas below the noise, a "
                  "local minimum or a scene unlike the experiment\n",
                  weighted_rms);
    reasons += line;
  }
  return reasons;
}

/// Refuses an `out` that cannot be written before any time is spent fitting.
void checkWritable(const std::string& path) {
  const bool existed = std::filesystem::exists(path);
  if (!std::ofstream(path, std::ios::app)) {
    throw FitSpecError("out: cannot write '" + path + "'");
  }
  if (!existed) std::filesystem::remove(path);
}

void writeOut(const identify::FitSpec& fit, const std::string& yaml,
              const std::vector<double>& values) {
  std::ofstream file(fit.out);
  file << identify::fittedSceneYaml(yaml, fit.fit, values);
  if (!file) throw std::runtime_error("out: cannot write '" + fit.out + "'");
}

}  // namespace

IdentifyResult identify(const IdentifyOptions& options, std::FILE* out) {
  const identify::FitSpec fit = identify::readFitSpec(options.fit_file);
  std::string yaml;
  std::optional<identify::Experiment> experiment;
  std::vector<double> guess;
  std::vector<long> outside;
  try {
    checkWritable(fit.out);
    identify::RecordedExperiment recorded = loadExperiment(fit, yaml, outside);
    guess = identify::firstGuess(recorded.scene, fit.fit);
    experiment.emplace(std::move(recorded), fit.fit);
  } catch (const FitSpecError& e) {
    throw FitSpecError(options.fit_file + ": " + e.what());
  }
  printOutside(out, fit, outside);
  const auto residuals = [&experiment](const std::vector<double>& values) {
    return experiment->residuals(experiment->simulate(values), values);
  };
  identify::FitOptions fit_options;
  fit_options.threads = options.threads;
  fit_options.max_iterations = options.max_iterations;
  fit_options.progress = [&](int iteration, double cost, const std::vector<double>& values) {
    std::fprintf(out, "iteration %d: cost %.6g%s\n", iteration, cost,
                 valuesText(fit.fit, values).c_str());
    std::fflush(out);
  };
  IdentifyResult result;
  result.fit = identify::fitLeastSquares(fit.fit, guess, experiment->residualCount(), residuals,
                                         fit_options);
  // The RMS of what was measured, not of the loss.
  const auto plain = [&experiment](const std::vector<double>& values) {
    return experiment->rms(experiment->residuals(experiment->simulate(values), values, true));
  };
  result.before = plain(guess);
  result.after = plain(result.fit.values);
  printFitted(out, fit, result.fit);
  printRms(out, fit, result.before, result.after);
  // About 1 when the sigmas are the noise; well above it in a local minimum.
  const double weighted_rms =
      std::sqrt(2.0 * result.fit.final_cost / static_cast<double>(experiment->residualCount()));
  std::fprintf(out,
               "weighted RMS residual %.3g (about 1 when the fit is right and sigma the noise)\n",
               weighted_rms);
  writeOut(fit, yaml, result.fit.values);
  std::fprintf(out, "wrote %s\n", fit.out.c_str());
  if (!options.plot.empty()) {
    identify::plotFit(*experiment, guess, result.fit.values, options.plot, options.plot_script,
                      options.plot_residuals);
  }
  const std::string reasons = distrust(fit, result.fit, weighted_rms);
  if (!result.fit.converged) {
    std::fprintf(out, "the fit did not converge: %s\n", result.fit.report.c_str());
    result.exit_code = 3;
  } else if (!reasons.empty()) {
    std::fprintf(out, "the fit cannot be trusted:\n%s", reasons.c_str());
    result.exit_code = 4;
  }
  return result;
}

}  // namespace deformable_sim::ros_layer
