#include "deformable_sim/core/session/resimulation.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <variant>

namespace deformable_sim::core {

namespace {

// The recording session checked every command against its own limits already.
CommandLimits unlimited() {
  const double infinity = std::numeric_limits<double>::infinity();
  return CommandLimits{infinity, infinity, infinity};
}

// The largest difference between two vectors of the same size, entry by entry.
double largestDifference(const Eigen::VectorXd& recorded, const Eigen::VectorXd& simulated) {
  if (recorded.size() == 0) return 0.0;
  return (recorded - simulated).cwiseAbs().maxCoeff();
}

bool isReset(const AppliedCommand& applied) {
  return std::holds_alternative<ResetCommand>(applied.command);
}

}  // namespace

Resimulation::Resimulation(SceneSpec spec, std::vector<Mesh> meshes, Recording recording,
                           SolverOverride solver,
                           std::vector<std::optional<EmbeddedSurface>> surfaces)
    : session_(std::move(spec), std::move(meshes), unlimited(), std::move(surfaces)),
      recording_(std::move(recording)),
      solver_(solver) {
  findStart();
  indexStates();
  planSteps();
  overrideSolver();
}

// The first (episode, step) the recording holds: of its first state, or of its first command
// when it holds no states.
std::pair<long, long> Resimulation::recordingStart() const {
  if (!recording_.states.empty()) {
    const auto& [episode, step, body] = recording_.states.begin()->first;
    return {episode, step};
  }
  if (!recording_.log.empty()) return {recording_.log.front().episode, 0};
  return {0, 0};
}

void Resimulation::findStart() {
  const auto [episode, step] = recordingStart();
  from_start_ = episode == 0 && step == 0;
  if (from_start_) return;
  const auto& log = recording_.log;
  while (first_command_ < log.size() && !isReset(log[first_command_])) ++first_command_;
  if (first_command_ == log.size()) {
    throw ResimulationError("the recording starts at step " + std::to_string(step) +
                            " of episode " + std::to_string(episode) +
                            " and holds no reset: record from the session's start or from a "
                            "reset");
  }
  // The reset's episode is the one it starts; the session before it is in episode 0.
  episode_offset_ = log[first_command_].episode - 1;
}

void Resimulation::indexStates() {
  const BodyList& bodies = session_.simulation().bodies();
  for (const auto& [key, state] : recording_.states) {
    const auto& [episode, step, name] = key;
    const int body = session_.simulation().bodyIndex(name);
    if (body < 0) continue;  // of a body the scene does not have: nothing to compare with
    std::vector<const RecordedState*>& slots = states_by_step_[{episode, step}];
    slots.resize(bodies.size(), nullptr);
    slots[body] = &state;
  }
}

void Resimulation::planSteps() {
  const long first_episode = from_start_ ? 0 : recording_.log[first_command_].episode;
  for (const auto& [episode_step, slots] : states_by_step_) {
    if (episode_step.first < first_episode) continue;
    long& end = end_steps_[episode_step.first];
    end = std::max(end, episode_step.second);
  }
  for (std::size_t k = first_command_; k < recording_.log.size(); ++k) {
    const AppliedCommand& applied = recording_.log[k];
    if (isReset(applied) || applied.episode < first_episode) continue;
    long& end = end_steps_[applied.episode];
    end = std::max(end, applied.step);
  }
  for (const auto& [episode, end] : end_steps_) planned_steps_ += end;
}

void Resimulation::extendTo(long episode, long step) {
  long& end = end_steps_[episode];
  if (step > end) planned_steps_ += step - end, end = step;
}

long Resimulation::endStep(long episode) const {
  const auto found = end_steps_.find(episode);
  return found == end_steps_.end() ? 0 : found->second;
}

ResimulationReport Resimulation::run(const Observer& observer, ProgressBar* progress) {
  if (ran_) throw std::logic_error("a Resimulation runs once: its session is where it ended");
  ran_ = true;
  observer_ = &observer;
  progress_ = progress;
  if (from_start_) compare();
  if (step_observer_) step_observer_(session_);
  for (std::size_t k = first_command_; k < recording_.log.size(); ++k) {
    const AppliedCommand& applied = recording_.log[k];
    // The reset the log starts at ends an episode that was not re-simulated.
    if (from_start_ || k != first_command_) {
      checkOrder(applied);
      stepTo(isReset(applied) ? endStep(recordedEpisode()) : applied.step);
    }
    apply(applied);
  }
  stepTo(endStep(recordedEpisode()));
  observer_ = nullptr;
  progress_ = nullptr;
  return report_;
}

void Resimulation::checkOrder(const AppliedCommand& applied) const {
  const long episode = recordedEpisode();
  const long expected = isReset(applied) ? episode + 1 : episode;
  const long step = session_.simulation().stepCount();
  if (applied.episode != expected || (!isReset(applied) && applied.step < step)) {
    throw ResimulationError("the log is out of order: a command of step " +
                            std::to_string(applied.step) + " of episode " +
                            std::to_string(applied.episode) + " after step " +
                            std::to_string(step) + " of episode " + std::to_string(episode));
  }
}

void Resimulation::apply(const AppliedCommand& applied) {
  try {
    session_.apply(applied.command);
  } catch (const CommandError&) {
    ++report_.refused_commands;  // only when the re-simulation went another way
    return;
  }
  const bool reset = isReset(applied);
  if (reset || std::holds_alternative<TuneCommand>(applied.command)) overrideSolver();
  if (reset) compare();
}

void Resimulation::overrideSolver() {
  if (!solver_.tolerance && !solver_.max_iterations) return;
  BodyTuning limits;
  limits.solver_tolerance = solver_.tolerance;
  limits.solver_max_iterations = solver_.max_iterations;
  for (Body& body : session_.simulation().bodies()) {
    body.tune(limits);
  }
}

void Resimulation::stepTo(long step) {
  Simulation& simulation = session_.simulation();
  while (simulation.stepCount() < step) {
    session_.step(step_reports_);
    for (const StepReport& body : step_reports_) report_.solver_iterations += body.solve.iterations;
    ++report_.steps;
    report_.simulated_time += simulation.dt();
    compare();
    if (step_observer_) step_observer_(session_);
    if (progress_) progress_->update(report_.steps);
  }
}

void Resimulation::compare() {
  const long episode = recordedEpisode();
  const auto found = states_by_step_.find({episode, session_.simulation().stepCount()});
  if (found == states_by_step_.end()) return;
  const std::vector<const RecordedState*>& slots = found->second;
  for (std::size_t b = 0; b < slots.size(); ++b) {
    if (slots[b]) compareBody(episode, static_cast<int>(b), *slots[b]);
  }
}

void Resimulation::compareBody(long episode, int b, const RecordedState& recorded) {
  const Simulation& simulation = session_.simulation();
  const Body& body = simulation.bodies()[b];
  const Eigen::Index size = 3 * static_cast<Eigen::Index>(body.numNodes());
  if (recorded.positions.size() != size || recorded.velocities.size() != size) {
    throw ResimulationError("the recorded state of body '" + body.name() +
                            "' has another number of nodes than its mesh");
  }
  ++report_.compared_states;
  const long step = simulation.stepCount();
  const double position = largestDifference(recorded.positions, body.positions());
  const double velocity = largestDifference(recorded.velocities, body.velocities());
  if ((position > 0.0 || velocity > 0.0) && report_.first_difference_step < 0) {
    report_.first_difference_episode = episode;
    report_.first_difference_step = step;
  }
  report_.max_position_difference = std::max(report_.max_position_difference, position);
  report_.max_velocity_difference = std::max(report_.max_velocity_difference, velocity);
  if (*observer_)
    (*observer_)(ComparedState{episode, step, b, simulation, recorded, position, velocity});
}

}  // namespace deformable_sim::core
