#include "deformable_sim/ros/sim_node.h"

#include <algorithm>

#include "deformable_sim/Scene.h"
#include "deformable_sim/core/outputs/body_activity.h"
#include "deformable_sim/io/scene_file.h"
#include "deformable_sim/ros/conversions.h"
#include "deformable_sim/ros/session_messages.h"
#include "deformable_sim/ros/voxel_progress_log.h"

namespace deformable_sim::ros_layer {

SimNode::SimNode(ros::NodeHandle& node, ros::NodeHandle& private_node)
    : params_(readNodeParameters(private_node)),
      wrench_timeouts_(params_.wrench_timeout_s),
      tf_listener_(tf_buffer_),
      frames_(tf_buffer_, params_.world_frame, params_.frame_prefix),
      robot_links_(params_.scene.urdf_file) {
  instants_.startEpisode(static_cast<int64_t>(ros::Time::now().toNSec()));
  startSession();
  auto apply = [this](const core::SessionCommand& c) { return this->apply(c); };
  obstacles_.emplace(params_, robot_links_, frames_, apply, private_node);
  status_.paused = params_.start_paused;
  applied_pub_ = private_node.advertise<Applied>("applied", 1000);
  scene_pub_ = private_node.advertise<Scene>("scene", 1, true);  // latched: a bag holds it
  publishScene();
  outputs_ = std::make_unique<NodeOutputs>(node, private_node, params_, *session_);
  if (sim().contact()) {
    contact_outputs_.emplace(private_node, params_.scene.urdf_links, params_.world_frame);
  }
  grasps_ = std::make_unique<NodeGrasps>(private_node, frames_, robot_links_, apply);
  tuning_ = std::make_unique<LiveTuning>(
      private_node, *session_, params_.rate_hz, params_.substeps, apply,
      [this](const std::string& reason) { refuse("~set_parameters", reason); },
      [this](double rate) {
        params_.rate_hz = rate;
        if (timer_.isValid()) timer_.setPeriod(ros::Duration(1.0 / rate));
        pacer_.restart(1.0 / rate);
      });
  subscribers_ = {private_node.subscribe("wrench", 100, &SimNode::onWrench, this),
                  private_node.subscribe("node_wrench", 100, &SimNode::onNodeWrench, this),
                  private_node.subscribe("fixed_nodes", 100, &SimNode::onFixedNodes, this),
                  private_node.subscribe("grasp", 100, &SimNode::onGrasp, this)};
  services_ = {private_node.advertiseService("grasp", &SimNode::onSetGrasp, this),
               private_node.advertiseService("reset", &SimNode::onReset, this),
               private_node.advertiseService("pause", &SimNode::onPause, this),
               private_node.advertiseService("resume", &SimNode::onResume, this),
               private_node.advertiseService("step", &SimNode::onStep, this)};
  pacer_.restart(1.0 / params_.rate_hz);
  timer_ = node.createTimer(ros::Duration(1.0 / params_.rate_hz), &SimNode::onTimer, this);
  logStart();
}

void SimNode::startSession() {
  std::vector<std::string> warnings;
  try {
    std::vector<std::optional<core::EmbeddedSurface>> surfaces;
    io::SurfaceSources sources = surfaceSources(params_.scene);
    sources.progress = voxelProgressLog();
    std::vector<core::Mesh> meshes = io::readMeshes(params_.scene, &warnings, &surfaces, sources);
    session_ = std::make_unique<core::Session>(params_.scene, std::move(meshes), params_.limits,
                                               std::move(surfaces));
  } catch (const core::SpecError& e) {
    throw std::runtime_error("~scene: " + io::locatedMessage(params_.scene, e));
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("~scene: ") + e.what());
  }
  for (const std::string& w : warnings) ROS_WARN("%s", w.c_str());
  session_->setListener([this](const core::AppliedCommand& applied) {
    recording_.header.stamp = shownInstant();  // the instant it takes effect at
    recording_.header.frame_id = params_.world_frame;
    recording_.episode = static_cast<uint64_t>(applied.episode);
    recording_.step = static_cast<uint64_t>(applied.step);
    applied_pub_.publish(recording_);
    markRecorded(recording_.meshes, obstacle_meshes_);
  });
  status_.reports.assign(session_->simulation().bodies().size(), core::StepReport{});
}

void SimNode::logStart() const {
  const core::Simulation& sim = session_->simulation();
  for (size_t b = 0; b < sim.bodies().size(); ++b) {
    ROS_INFO("%s; frame '%s'", core::bodySummary(sim, static_cast<int>(b)).c_str(),
             (params_.frame_prefix + sim.bodies()[b].name()).c_str());
  }
  if (!params_.rate_note.empty()) ROS_WARN("%s", params_.rate_note.c_str());
  ROS_INFO("stepping %s at %.4g Hz x %d substeps (dt %.4g s) in frame '%s'",
           params_.scene_path.empty() ? "the built-in default scene" : params_.scene_path.c_str(),
           params_.rate_hz, params_.substeps, sim.dt(), params_.world_frame.c_str());
}

int SimNode::apply(const core::SessionCommand& command) {
  // Applied as recorded: the command read back from the very message published on ~applied, so
  // that a replay of it acts exactly as it did here (a pose's quaternion does not round-trip).
  recording_ = toMessage(command, obstacle_meshes_);
  return session_->apply(fromMessage(recording_, obstacle_meshes_));
}

void SimNode::publishScene() {
  std::vector<std::string> names;
  for (const core::BodySpec& body : params_.scene.bodies) names.push_back(body.name);
  Scene message =
      toSceneMessage(params_.scene_path, params_.scene_text, sim().dt(), params_.substeps,
                     session_->meshes(), session_->surfaces(), names, params_.scene.obstacles,
                     robot_links_.shapes(params_.scene.urdf_links), obstacle_meshes_);
  message.header.stamp = ros::Time::now();
  message.header.frame_id = params_.world_frame;
  message.world_frame = params_.world_frame;
  message.frame_prefix = params_.frame_prefix;
  scene_pub_.publish(message);
}

void SimNode::onTimer(const ros::TimerEvent&) {
  const ros::Time now = ros::Time::now();
  bool stepped = false;
  for (const std::string& source : wrench_timeouts_.expire(now.toSec())) {
    apply(core::ClearWrenchCommand{source});
  }
  // A body must not fall through an obstacle that tf has not delivered yet: wait for them all.
  if (sim().contact() && !obstacles_->update(now)) {
    ROS_INFO_THROTTLE(2.0, "waiting for tf to place the obstacle links before stepping");
    pacer_.restart(1.0 / params_.rate_hz);
  } else if (status_.paused) {
    pacer_.restart(1.0 / params_.rate_hz);
  } else {
    // The ticks a late callback missed too (core/driver/tick_pacer.h); none owed, nothing new
    // to publish either (a state twice with one step would be recorded twice).
    const int ticks = pacer_.ticksDue(now.toSec());
    if (ticks == 0) return;
    advance(params_.substeps * ticks);
    instants_.stepped(sim().time(), static_cast<int64_t>(now.toNSec()));
    stepped = true;
  }
  real_time_factor_.sample(now.toSec(), sim().time());
  status_.real_time_factor = real_time_factor_.value();
  watchRealTime(stepped);
  status_.recent_recovery =
      !last_recovery_.isZero() && (ros::WallTime::now() - last_recovery_).toSec() < 2.0;
  publishState(now);
  outputs_->publishPeriodic(*session_, status_, refusals_, now, shownInstant());
}

void SimNode::watchRealTime(bool stepped) {
  const double wall = ros::WallTime::now().toSec();
  slow_ticks_.sample(wall, status_.real_time_factor, stepped);
  status_.slow = slow_ticks_.slow();
  if (status_.slow) {
    ROS_WARN_THROTTLE(10.0, "slower than real time for %.0f s (%.2g x real time): %s",
                      slow_ticks_.slowFor(wall), status_.real_time_factor,
                      core::costliestPart(status_).c_str());
  }
}

void SimNode::advance(int steps) {
  grasps_->planMoves(session_->commands());
  const ros::WallTime start = ros::WallTime::now();
  for (int s = 1; s <= steps; ++s) {
    grasps_->move(s, steps);
    session_->step(status_.reports);
  }
  status_.step_time_s = (ros::WallTime::now() - start).toSec();
  status_.steps = steps;
  long recoveries = 0;  // the watchdog's (core::Simulation::step): counted, warned, diagnosed
  for (size_t b = 0; b < sim().bodies().size(); ++b) {
    recoveries += sim().recoveries(static_cast<int>(b));
    const core::StepReport& report = status_.reports[b];
    if (report.recovered) {
      status_.recovery_from_leap = report.energy_leapt;
      ROS_WARN_THROTTLE(1.0,
                        "body '%s': step %ld %s; the watchdog restored the last good positions "
                        "and stopped the body",
                        sim().bodies()[b].name().c_str(), sim().stepCount(),
                        report.energy_leapt ? "gained far more energy than its inputs could give"
                                            : "left a non-finite value");
    }
  }
  if (recoveries > status_.recoveries) last_recovery_ = ros::WallTime::now();
  status_.recoveries = recoveries;  // a reset starts the count again
}

ros::Time SimNode::shownInstant() const {
  ros::Time stamp;
  // A clock not yet started (simulated time before /clock) has no earlier time to give.
  stamp.fromNSec(
      static_cast<uint64_t>(std::max<int64_t>(0, instants_.stamp(session_->simulation().time()))));
  return stamp;
}

void SimNode::publishState(const ros::Time& now) {
  const ros::Time stamp = shownInstant();
  const bool tf_sent = outputs_->publishState(*session_, stamp);
  if (contact_outputs_) {
    contact_outputs_->publish(
        *session_,
        [this, &now](const std::string& link) { return obstacles_->linkPose(link, now, nullptr); },
        stamp);
  }
  grasps_->publish(*session_, stamp, tf_sent ? &outputs_->broadcaster() : nullptr);
}

void SimNode::refuse(const std::string& topic, const std::string& reason) {
  const std::string warning = refusals_.refuse(topic, reason, ros::WallTime::now().toSec());
  if (!warning.empty()) ROS_WARN("%s", warning.c_str());
}

void SimNode::onWrench(const geometry_msgs::WrenchStamped::ConstPtr& message) {
  const std::string frame = withoutLeadingSlash(message->header.frame_id);
  const Eigen::Vector3d force = toEigen(message->wrench.force);
  const Eigen::Vector3d torque = toEigen(message->wrench.torque);
  const bool zero = force.isZero(0.0) && torque.isZero(0.0);
  try {
    if (frame.empty()) {
      throw core::CommandError(
          "header.frame_id is empty: name a body, a node group (<body>/<group>) or a tf frame");
    }
    // A zero wrench removes the frame's wrench without resolving the frame (it may have left tf);
    // one that removes nothing must name a frame a wrench could act on, like any other wrench.
    if (zero && session_->commands().activeWrenches().count(frame) > 0) {
      apply(core::ClearWrenchCommand{frame});
    } else {
      apply(core::wrenchInFrame(sim(), frame, frames_.resolve(sim(), frame), force, torque));
    }
    wrench_timeouts_.heard(frame, ros::Time::now().toSec(), zero);
  } catch (const core::CommandError& e) {
    refuse("~wrench", e.what());
  }
}

void SimNode::onNodeWrench(const NodeWrench::ConstPtr& message) {
  try {
    const core::BodyFrame frame = frames_.resolve(sim(), message->header.frame_id);
    const core::WrenchCommand command = toCommand(*message, frame.pose);
    apply(command);
    wrench_timeouts_.heard(command.source, ros::Time::now().toSec(),
                           command.force.isZero(0.0) && command.torque.isZero(0.0));
  } catch (const core::CommandError& e) {
    refuse("~node_wrench", e.what());
  }
}

void SimNode::onFixedNodes(const FixedNodes::ConstPtr& message) {
  try {
    apply(toCommand(*message, frames_.resolve(sim(), message->header.frame_id).pose));
  } catch (const core::CommandError& e) {
    refuse("~fixed_nodes", e.what());
  }
}

void SimNode::onGrasp(const Grasp::ConstPtr& message) {
  try {
    grasps_->handle(*session_, *message);
  } catch (const core::CommandError& e) {
    refuse("~grasp", e.what());
  }
}

bool SimNode::onSetGrasp(SetGrasp::Request& request, SetGrasp::Response& response) {
  try {
    response.nodes = grasps_->handle(*session_, request.grasp);
    response.success = true;
    response.message = (request.grasp.action == Grasp::ATTACH ? "attached " : "released ") +
                       std::to_string(response.nodes) + " nodes";
  } catch (const core::CommandError& e) {
    response.success = false;
    response.message = e.what();
    refuse("~grasp (service)", e.what());
  }
  return true;
}

bool SimNode::onReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  instants_.startEpisode(static_cast<int64_t>(ros::Time::now().toNSec()));
  apply(core::ResetCommand{});
  wrench_timeouts_.clear();
  grasps_->clear();
  real_time_factor_.clear();
  slow_ticks_.clear();
  status_.reports.assign(sim().bodies().size(), core::StepReport{});
  obstacles_->forget();
  tuning_->reapply();  // keep what was tuned live
  publishState(ros::Time::now());
  response.success = true;
  response.message = "reset to the scene's initial state";
  return true;
}

bool SimNode::onPause(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  response.success = true;
  response.message =
      status_.paused ? "already paused" : "paused at step " + std::to_string(sim().stepCount());
  status_.paused = true;
  return true;
}

bool SimNode::onResume(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  response.success = true;
  response.message =
      status_.paused ? "resumed at step " + std::to_string(sim().stepCount()) : "not paused";
  status_.paused = false;
  return true;
}

bool SimNode::onStep(Step::Request& request, Step::Response& response) {
  response.success = false;
  if (!status_.paused) {
    response.message = "not paused: call ~pause first";
  } else if (request.steps > static_cast<uint32_t>(params_.max_steps_per_call)) {
    response.message = "refused " + std::to_string(request.steps) + " steps: at most " +
                       std::to_string(params_.max_steps_per_call) +
                       " a call (~max_steps_per_call); call again for more";
  } else if (sim().contact() && !obstacles_->update(ros::Time::now())) {
    response.message = "waiting for tf to place the obstacle links";
  } else {
    const ros::Time now = ros::Time::now();
    if (request.steps > 0) advance(static_cast<int>(request.steps));
    instants_.stepped(sim().time(), static_cast<int64_t>(now.toNSec()));
    publishState(now);
    response.success = true;
    response.message = "took " + std::to_string(request.steps) + " steps";
  }
  response.step = static_cast<uint64_t>(sim().stepCount());
  return true;
}

}  // namespace deformable_sim::ros_layer
