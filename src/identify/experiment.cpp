#include "deformable_sim/identify/experiment.h"

#include <cmath>
#include <variant>

#include "deformable_sim/identify/observation_model.h"
#include "deformable_sim/identify/scene_parameter.h"

namespace deformable_sim::identify {

namespace {

std::vector<ObservationModel> models(const RecordedExperiment& recorded,
                                     const core::Simulation& simulation) {
  std::vector<ObservationModel> list;
  for (std::size_t o = 0; o < recorded.observations.size(); ++o) {
    // A moving sensor's wrench is predicted in the world and seen from its frame per sample.
    const bool moving = !recorded.measured[o].frames.empty();
    list.emplace_back(recorded.observations[o], simulation,
                      moving ? Eigen::Isometry3d::Identity() : recorded.sensor_frames[o]);
  }
  return list;
}

double lastTime(const std::vector<MeasuredSeries>& measured) {
  double last = 0.0;
  for (const MeasuredSeries& series : measured) {
    if (!series.times.empty()) last = std::max(last, series.times.back());
  }
  return last;
}

}  // namespace

long measuredEpisode(const core::Recording& recording) {
  if (recording.log.empty() || recording.log.front().episode == 0) return 0;
  for (const core::AppliedCommand& applied : recording.log) {
    if (std::holds_alternative<core::ResetCommand>(applied.command)) return applied.episode;
  }
  return recording.log.front().episode;  // the Resimulation refuses such a log
}

Experiment::Experiment(RecordedExperiment recorded, std::vector<FitParameter> parameters)
    : recorded_(std::move(recorded)), parameters_(std::move(parameters)) {
  recorded_.sensor_frames.resize(recorded_.observations.size(), Eigen::Isometry3d::Identity());
  const core::Simulation probe(recorded_.scene, recorded_.meshes);
  models(recorded_, probe);  // throws for observations the scene cannot give
  episode_ = measuredEpisode(recorded_.recording);
  last_step_ = static_cast<long>(std::ceil(lastTime(recorded_.measured) / recorded_.scene.dt)) + 1;
  for (std::size_t o = 0; o < recorded_.observations.size(); ++o) {
    const long size = recorded_.observations[o].kind == ObservationSpec::Kind::kFrame ? 3 : 6;
    residual_count_ += size * static_cast<long>(recorded_.measured[o].times.size());
  }
}

core::SceneSpec Experiment::trialScene(const std::vector<double>& values) const {
  core::SceneSpec scene = recorded_.scene;
  for (std::size_t p = 0; p < parameters_.size(); ++p)
    setParameter(scene, parameters_[p], values[p]);
  scene.solver.threads = 1;  // trials run side by side, each on one thread
  return scene;
}

std::vector<SimulatedSeries> Experiment::simulate(const std::vector<double>& values) const {
  core::Resimulation resimulation(trialScene(values), recorded_.meshes, recorded_.recording, {},
                                  recorded_.surfaces);
  resimulation.extendTo(episode_, last_step_);
  std::vector<ObservationModel> observers = models(recorded_, resimulation.session().simulation());
  std::vector<SimulatedSeries> series(observers.size());
  for (SimulatedSeries& s : series) s.dt = recorded_.scene.dt;
  // The observer first hears of the scene as built (step 0, as after the reset a log may start
  // at), then of every step; it keeps the first episode it hears of.
  long episode = -1;
  resimulation.setStepObserver([&](const core::Session& session) {
    if (session.episode() != episode) {
      if (series.empty() || series.front().steps.size() > 1) return;  // a later episode
      episode = session.episode();
    }
    for (std::size_t o = 0; o < observers.size(); ++o)
      series[o].steps.push_back(observers[o].predict(session));
  });
  resimulation.run();
  return series;
}

double Experiment::timeOffset(std::size_t o, const std::vector<double>& values) const {
  for (std::size_t p = 0; p < parameters_.size(); ++p) {
    if (parameters_[p].observation == static_cast<int>(o)) return values[p];
  }
  return recorded_.observations[o].time_offset;
}

Eigen::VectorXd Experiment::predicted(std::size_t o, std::size_t s,
                                      const SimulatedSeries& simulated,
                                      const std::vector<double>& values) const {
  const MeasuredSeries& measured = recorded_.measured[o];
  Eigen::VectorXd value = simulated.at(measured.times[s] - timeOffset(o, values));
  if (measured.frames.empty()) return value;
  const core::Wrench seen = core::seenFrom(
      core::Wrench{value.head<3>(), value.tail<3>(), Eigen::Vector3d::Zero()}, measured.frames[s]);
  value << seen.force, seen.torque;
  return value;
}

Eigen::VectorXd Experiment::residuals(const std::vector<SimulatedSeries>& simulated,
                                      const std::vector<double>& values, bool plain) const {
  Eigen::VectorXd r(residual_count_);
  Eigen::Index at = 0;
  for (std::size_t o = 0; o < simulated.size(); ++o) {
    const ObservationSpec& spec = recorded_.observations[o];
    const MeasuredSeries& measured = recorded_.measured[o];
    for (std::size_t s = 0; s < measured.times.size(); ++s) {
      const Eigen::VectorXd d = predicted(o, s, simulated[o], values) - measured.values[s];
      auto sample = r.segment(at, d.size());
      if (d.size() == 3) {
        sample = d / spec.sigma;
      } else {
        sample.head<3>() = d.head<3>() / spec.sigma;
        sample.tail<3>() = d.tail<3>() / spec.torque_sigma;
      }
      // Huber's loss on the sample's squared norm q: q within h^2, else 2 h sqrt(q) - h^2, by
      // scaling the sample so that its square is that.
      const double q = sample.squaredNorm(), h = spec.huber;
      if (!plain && h > 0.0 && q > h * h) sample *= std::sqrt((2.0 * h * std::sqrt(q) - h * h) / q);
      at += d.size();
    }
  }
  return r;
}

std::vector<ObservationRms> Experiment::rms(const Eigen::VectorXd& residuals) const {
  std::vector<ObservationRms> result;
  Eigen::Index at = 0;
  for (std::size_t o = 0; o < recorded_.observations.size(); ++o) {
    const ObservationSpec& spec = recorded_.observations[o];
    const long samples = static_cast<long>(recorded_.measured[o].times.size());
    const int size = spec.kind == ObservationSpec::Kind::kFrame ? 3 : 6;
    Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>> block(
        residuals.data() + at, 3, samples * size / 3, Eigen::OuterStride<>(3));
    at += samples * size;
    ObservationRms value;
    if (samples == 0) {
      result.push_back(value);
      continue;
    }
    if (size == 3) {
      value.first = spec.sigma * std::sqrt(block.squaredNorm() / (3.0 * samples));
    } else {
      // Columns alternate force, torque.
      double force = 0.0, torque = 0.0;
      for (long s = 0; s < samples; ++s) {
        force += block.col(2 * s).squaredNorm();
        torque += block.col(2 * s + 1).squaredNorm();
      }
      value.first = spec.sigma * std::sqrt(force / (3.0 * samples));
      value.second = spec.torque_sigma * std::sqrt(torque / (3.0 * samples));
    }
    result.push_back(value);
  }
  return result;
}

}  // namespace deformable_sim::identify
