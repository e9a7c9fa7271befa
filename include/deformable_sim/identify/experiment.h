// A recorded experiment to fit: the scene and the log of commands of a session, and what was
// measured during it. Re-simulates the log with trial parameter values (the core's
// Resimulation, as deformable_sim_replay does) and compares the result with the measurements.
#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "deformable_sim/core/session/resimulation.h"
#include "deformable_sim/identify/fit_spec.h"
#include "deformable_sim/identify/observed_series.h"

namespace deformable_sim::identify {

struct RecordedExperiment {
  core::SceneSpec scene;  ///< its values are the first guess
  std::vector<core::Mesh> meshes;
  std::vector<std::optional<core::EmbeddedSurface>> surfaces;
  core::Recording recording;  ///< the log; recorded states are not needed
  std::vector<ObservationSpec> observations;
  std::vector<Eigen::Isometry3d> sensor_frames;  ///< per observation: a wrench's frame, world
  std::vector<MeasuredSeries> measured;          ///< per observation
};

/// RMS of one observation's residuals: position (m), or force (N) and torque (N m).
struct ObservationRms {
  double first = 0.0;
  double second = 0.0;  ///< torque; zero for a position
};

/// The episode a fit compares: the session's first (0) when the log starts there, else the one
/// its first reset starts, as the Resimulation does. The measurements' times count from its
/// step 0.
long measuredEpisode(const core::Recording& recording);

class Experiment {
 public:
  /// Builds the scene once to check the observations against it; throws FitSpecError naming the
  /// key (an unknown body, `at` outside its body), std::invalid_argument for a bad scene.
  Experiment(RecordedExperiment recorded, std::vector<FitParameter> parameters);

  const RecordedExperiment& recorded() const { return recorded_; }
  /// Weighted residuals (simulated - measured) / sigma, all observations' samples in turn.
  long residualCount() const { return residual_count_; }

  /// Every observation at every step, the scene given `values` of the parameters. Thread-safe.
  std::vector<SimulatedSeries> simulate(const std::vector<double>& values) const;
  /// The weighted residuals of `simulated` (with the parameters' `values`: time offsets), each
  /// sample's through its observation's loss unless `plain`.
  Eigen::VectorXd residuals(const std::vector<SimulatedSeries>& simulated,
                            const std::vector<double>& values, bool plain = false) const;
  std::vector<ObservationRms> rms(const Eigen::VectorXd& residuals) const;
  /// Observation o's time offset (s) with the parameters' `values`: fitted, or as given.
  double timeOffset(std::size_t o, const std::vector<double>& values) const;
  /// What observation o's sample s is compared with: `simulated` at its time less the offset,
  /// in its frame then (a moving sensor's).
  Eigen::VectorXd predicted(std::size_t o, std::size_t s, const SimulatedSeries& simulated,
                            const std::vector<double>& values) const;

 private:
  core::SceneSpec trialScene(const std::vector<double>& values) const;

  RecordedExperiment recorded_;
  std::vector<FitParameter> parameters_;
  long episode_ = 0;    ///< measuredEpisode
  long last_step_ = 0;  ///< the step after the last sample
  long residual_count_ = 0;
};

}  // namespace deformable_sim::identify
