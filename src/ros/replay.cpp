#include "deformable_sim/ros/replay.h"

#include <rosbag/bag.h>
#include <rosbag/exceptions.h>
#include <rosbag/view.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/Marker.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <tuple>

#include "deformable_sim/Applied.h"
#include "deformable_sim/BodyState.h"
#include "deformable_sim/Scene.h"
#include "deformable_sim/core/default_scene.h"
#include "deformable_sim/core/session.h"
#include "deformable_sim/core/strain.h"
#include "deformable_sim/io/scene_file.h"
#include "deformable_sim/ros/body_frames.h"
#include "deformable_sim/ros/conversions.h"
#include "deformable_sim/ros/markers.h"
#include "deformable_sim/ros/session_messages.h"

namespace deformable_sim::ros_layer {

namespace {

using StateKey = std::tuple<long, long, std::string>;  // episode, step, body

struct Recording {
  std::string node;
  Scene scene;
  std::vector<Applied> applied;
  std::map<StateKey, BodyState> states;  // the first one of each key (a paused node repeats it)
};

std::string sceneTopicNode(const std::string& topic) {
  const std::string suffix = "/scene";
  return topic.substr(0, topic.size() - suffix.size());
}

Recording readRecording(const ReplayOptions& options) {
  Recording recording;
  rosbag::Bag bag;
  try {
    bag.open(options.input, rosbag::bagmode::Read);
    std::set<std::string> nodes;
    rosbag::View scenes(bag, rosbag::TypeQuery("deformable_sim/Scene"));
    for (const rosbag::ConnectionInfo* connection : scenes.getConnections()) {
      nodes.insert(sceneTopicNode(connection->topic));
    }
    if (nodes.empty()) {
      throw ReplayError(options.input +
                        ": no deformable_sim/Scene message: record the node's ~scene topic "
                        "(latched) with the session, e.g. rosbag record -a");
    }
    if (options.node.empty() && nodes.size() > 1) {
      std::string list;
      for (const std::string& n : nodes) list += (list.empty() ? "" : ", ") + n;
      throw ReplayError(options.input + ": sessions of several nodes (" + list +
                        "): choose one with --node");
    }
    recording.node = options.node.empty() ? *nodes.begin() : options.node;
    if (nodes.count(recording.node) == 0) {
      throw ReplayError(options.input + ": no scene of node '" + recording.node + "'");
    }
    const std::string node = recording.node;
    rosbag::View view(bag,
                      rosbag::TopicQuery({node + "/scene", node + "/applied", node + "/state"}));
    bool have_scene = false;
    for (const rosbag::MessageInstance& m : view) {
      if (m.getTopic() == node + "/scene") {
        const Scene::ConstPtr scene = m.instantiate<Scene>();
        if (!scene) throw ReplayError(options.input + ": ~scene is of another version of Scene");
        if (!have_scene) recording.scene = *scene;
        have_scene = true;
      } else if (m.getTopic() == node + "/applied") {
        const Applied::ConstPtr applied = m.instantiate<Applied>();
        if (!applied) throw ReplayError(options.input + ": ~applied is of another version");
        recording.applied.push_back(*applied);
      } else {
        const BodyState::ConstPtr state = m.instantiate<BodyState>();
        if (!state) throw ReplayError(options.input + ": ~state is of another version");
        recording.states.emplace(StateKey{static_cast<long>(state->episode),
                                          static_cast<long>(state->step), state->body},
                                 *state);
      }
    }
  } catch (const rosbag::BagUnindexedException&) {
    throw ReplayError(options.input +
                      ": the bag has no index: it was truncated or its recording did not end "
                      "cleanly (rosbag reindex may repair it)");
  } catch (const rosbag::BagException& e) {
    throw ReplayError(options.input + ": cannot read the bag: " + e.what());
  }
  return recording;
}

core::SceneSpec sceneSpec(const Scene& scene) {
  core::SceneSpec spec;
  if (scene.yaml.empty()) {
    spec = core::defaultScene();
  } else {
    const std::string directory = std::filesystem::path(scene.path).parent_path().string();
    try {
      spec = io::parseScene(scene.yaml, scene.path.empty() ? "~scene" : scene.path,
                            directory.empty() ? "." : directory);
    } catch (const io::SceneError& e) {
      throw ReplayError(std::string("the recorded scene: ") + e.what());
    }
  }
  spec.dt = scene.dt;
  return spec;
}

// The largest difference between recorded points or vectors and the 3n entries of x.
template <typename Entry>
double maxDifference(const std::vector<Entry>& recorded, const Eigen::VectorXd& x) {
  double largest = 0.0;
  for (size_t i = 0; i < recorded.size(); ++i) {
    largest = std::max(largest, std::abs(recorded[i].x - x[3 * i]));
    largest = std::max(largest, std::abs(recorded[i].y - x[3 * i + 1]));
    largest = std::max(largest, std::abs(recorded[i].z - x[3 * i + 2]));
  }
  return largest;
}

class ProgressBar {
 public:
  ProgressBar(std::ostream* out, size_t total) : out_(out), total_(std::max<size_t>(total, 1)) {}
  void update(size_t done) {
    const int percent = static_cast<int>(100 * done / total_);
    if (!out_ || percent == shown_) return;
    shown_ = percent;
    const int width = 40, filled = width * percent / 100;
    *out_ << "\r[" << std::string(filled, '#') << std::string(width - filled, ' ') << "] "
          << percent << "% " << std::flush;
    if (percent == 100) *out_ << "\n";
  }

 private:
  std::ostream* out_;
  size_t total_;
  int shown_ = -1;
};

}  // namespace

ReplayReport replay(const ReplayOptions& options, std::ostream* progress) {
  Recording recording = readRecording(options);
  ReplayReport report;
  report.node = recording.node;
  const Scene& scene = recording.scene;

  core::SceneSpec spec = sceneSpec(scene);
  if (options.solver_method) {
    if (*options.solver_method == "cg") {
      spec.solver.method = core::SolverSettings::Method::kConjugateGradient;
    } else if (*options.solver_method == "direct") {
      spec.solver.method = core::SolverSettings::Method::kDirect;
    } else {
      throw ReplayError("--solver: '" + *options.solver_method + "' is neither cg nor direct");
    }
  }
  if (options.solver_tolerance) spec.solver.tolerance = *options.solver_tolerance;
  if (options.solver_max_iterations) spec.solver.max_iterations = *options.solver_max_iterations;
  if (options.threads) spec.solver.threads = *options.threads;
  report.threads = spec.solver.threads;
  std::vector<core::Mesh> meshes;
  try {
    meshes = meshesFromMessage(scene);
  } catch (const std::invalid_argument& e) {
    throw ReplayError(e.what());
  }
  // The node checked every recorded command against its own limits already.
  const double unlimited = std::numeric_limits<double>::infinity();
  std::unique_ptr<core::Session> session;
  try {
    session = std::make_unique<core::Session>(spec, meshes,
                                              core::CommandLimits{unlimited, unlimited, unlimited});
  } catch (const std::invalid_argument& e) {
    throw ReplayError(std::string("the recorded scene: ") + e.what());
  }
  auto overrideSolver = [&]() {
    for (core::Body& body : session->simulation().bodies()) {
      body.setSolverLimits(
          options.solver_tolerance.value_or(body.solverSettings().tolerance),
          options.solver_max_iterations.value_or(body.solverSettings().max_iterations));
    }
  };

  // Where the log starts: at the node's start (episode 0, step 0) or at a reset.
  long episode_offset = 0;
  size_t first = 0;
  const bool from_start =
      recording.states.empty() || (std::get<0>(recording.states.begin()->first) == 0 &&
                                   std::get<1>(recording.states.begin()->first) == 0);
  if (!from_start) {
    while (first < recording.applied.size() && recording.applied[first].kind != Applied::RESET) {
      ++first;
    }
    if (first == recording.applied.size()) {
      const auto& [episode, step, body] = recording.states.begin()->first;
      throw ReplayError(options.input + ": the recording starts at step " + std::to_string(step) +
                        " of episode " + std::to_string(episode) +
                        " and holds no reset: start rosbag record before the node, or call ~reset "
                        "after it started");
    }
    episode_offset = static_cast<long>(recording.applied[first].episode) - 1;
  }

  rosbag::Bag out;
  if (!options.output.empty()) {
    try {
      out.open(options.output, rosbag::bagmode::Write);
    } catch (const rosbag::BagException& e) {
      throw ReplayError(options.output + ": cannot write: " + e.what());
    }
    out.write(recording.node + "/scene",
              scene.header.stamp.isZero() ? ros::TIME_MIN : scene.header.stamp, scene);
  }
  std::vector<std::vector<core::Triangle>> surfaces;
  for (const core::Body& body : session->simulation().bodies()) {
    surfaces.push_back(core::extractSurface(body.mesh()));
  }
  visualization_msgs::Marker mesh_message;
  std::vector<double> strain;
  double next_marker_time = 0.0;
  BodyState state_message;

  // Compares (and writes) the states recorded at this step of this episode.
  auto compare = [&]() {
    const core::Simulation& sim = session->simulation();
    const long episode = session->episode() + episode_offset;
    bool marker_due = sim.time() >= next_marker_time;
    for (size_t b = 0; b < sim.bodies().size(); ++b) {
      const core::Body& body = sim.bodies()[b];
      const auto found = recording.states.find(StateKey{episode, sim.stepCount(), body.name()});
      if (found == recording.states.end()) continue;
      const BodyState& recorded = found->second;
      if (recorded.positions.size() != static_cast<size_t>(body.numNodes())) {
        throw ReplayError("the recorded state of body '" + body.name() +
                          "' has another number of nodes than its recorded mesh");
      }
      ++report.compared_states;
      const double position = maxDifference(recorded.positions, body.positions());
      const double velocity = maxDifference(recorded.velocities, body.velocities());
      if ((position > 0.0 || velocity > 0.0) && report.first_difference_step < 0) {
        report.first_difference_episode = episode;
        report.first_difference_step = sim.stepCount();
      }
      report.max_position_difference = std::max(report.max_position_difference, position);
      report.max_velocity_difference = std::max(report.max_velocity_difference, velocity);
      if (options.output.empty()) continue;
      const ros::Time stamp =
          recorded.header.stamp.isZero() ? ros::TIME_MIN : recorded.header.stamp;
      fillState(body, state_message);
      state_message.header = recorded.header;
      state_message.episode = recorded.episode;
      state_message.step = recorded.step;
      out.write(recording.node + "/state", stamp, state_message);
      if (b == 0) {
        tf2_msgs::TFMessage tf;
        tf.transforms = bodyFrames(sim.bodies(), scene.world_frame, scene.frame_prefix, stamp);
        out.write("/tf", stamp, tf);
      }
      if (marker_due) {
        const bool colour = body.effects().stress_colouring;
        if (colour) core::nodalStrain(body, strain);
        fillSurfaceMarker(body, surfaces[b], colour ? &strain : nullptr, 0.1, mesh_message);
        mesh_message.header = recorded.header;
        out.write(recording.node + "/mesh", stamp, mesh_message);
      }
    }
    if (marker_due) next_marker_time = sim.time() + 1.0 / options.marker_rate;
  };

  long last_step = 0;  // of the last episode: how far to run after the last command
  if (!recording.states.empty()) {
    const long last_episode = std::get<0>(recording.states.rbegin()->first);
    for (const auto& [key, state] : recording.states) {
      if (std::get<0>(key) == last_episode) last_step = std::max(last_step, std::get<1>(key));
    }
  }
  size_t total_steps = 0;  // for the progress bar: an estimate from the log
  for (size_t k = first; k < recording.applied.size(); ++k) {
    if (recording.applied[k].kind == Applied::RESET && k > first) {
      total_steps += recording.applied[k - 1].step;
    }
  }
  total_steps += static_cast<size_t>(last_step);
  ProgressBar bar(progress, total_steps);

  std::vector<core::StepReport> reports;
  const auto start = std::chrono::steady_clock::now();
  auto stepTo = [&](long step) {
    core::Simulation& sim = session->simulation();
    while (sim.stepCount() < step) {
      session->step(reports);
      for (const core::StepReport& body : reports)
        report.solver_iterations += body.solve.iterations;
      ++report.steps;
      report.simulated_time += sim.dt();
      compare();
      bar.update(report.steps);
    }
  };
  if (from_start) compare();
  for (size_t k = first; k < recording.applied.size(); ++k) {
    const Applied& applied = recording.applied[k];
    if (applied.kind != Applied::RESET) {
      if (static_cast<long>(applied.episode) != session->episode() + episode_offset) {
        throw ReplayError("the log is out of order: a command of episode " +
                          std::to_string(applied.episode) + " in episode " +
                          std::to_string(session->episode() + episode_offset));
      }
      stepTo(static_cast<long>(applied.step));
    }
    try {
      session->apply(fromMessage(applied));
      if (applied.kind == Applied::RESET) {
        if (options.solver_tolerance || options.solver_max_iterations) overrideSolver();
        compare();
      } else if (applied.kind == Applied::TUNE &&
                 (options.solver_tolerance || options.solver_max_iterations)) {
        overrideSolver();
      }
    } catch (const core::CommandError&) {
      ++report.refused_commands;  // only when the re-simulation went another way
    }
  }
  stepTo(last_step);
  bar.update(total_steps);
  report.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!options.output.empty()) out.close();
  return report;
}

}  // namespace deformable_sim::ros_layer
