#include "deformable_sim/ros/sim_node.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "deformable_sim/core/default_scene.h"
#include "deformable_sim/core/rigid_frame.h"
#include "deformable_sim/core/strain.h"
#include "deformable_sim/io/scene_file.h"
#include "deformable_sim/io/urdf_shapes.h"
#include "deformable_sim/ros/body_frames.h"
#include "deformable_sim/ros/conversions.h"
#include "deformable_sim/ros/markers.h"
#include "deformable_sim/ros/session_messages.h"

namespace deformable_sim::ros_layer {

namespace {

std::string withoutLeadingSlash(const std::string& frame) {
  return !frame.empty() && frame[0] == '/' ? frame.substr(1) : frame;
}

// Reads a private parameter, keeping `value` (the default) when it is not set.
template <typename T>
void param(ros::NodeHandle& node, const std::string& name, T& value) {
  node.param(name, value, value);
}

}  // namespace

SimNode::SimNode(ros::NodeHandle& node, ros::NodeHandle& private_node)
    : private_node_(private_node), tf_listener_(tf_buffer_), diagnostics_(node, private_node) {
  readParameters(private_node);
  buildSimulation();

  if (!scene_.urdf_links.empty()) {
    std::string error;
    if (!loadUrdf(error)) throw std::runtime_error("urdf.links: " + error);
    for (const std::string& link : scene_.urdf_links) {
      try {
        for (const core::PlacedShape& shape : io::linkShapes(urdf_shapes_, link)) {
          link_obstacles_.push_back({link, shape, std::nullopt});
        }
      } catch (const io::UrdfError& e) {
        throw std::runtime_error(std::string("urdf.links: ") + e.what());
      }
    }
  }

  applied_pub_ = private_node.advertise<Applied>("applied", 1000);
  scene_pub_ = private_node.advertise<Scene>("scene", 1, true);  // latched: a bag holds it
  publishScene();
  state_pub_ = private_node.advertise<BodyState>("state", 10);
  stats_pub_ = private_node.advertise<Stats>("stats", 10);
  mesh_pub_ = private_node.advertise<visualization_msgs::Marker>("mesh", 2);
  markers_pub_ = private_node.advertise<visualization_msgs::MarkerArray>("markers", 2);
  wrench_sub_ = private_node.subscribe("wrench", 100, &SimNode::onWrench, this);
  node_wrench_sub_ = private_node.subscribe("node_wrench", 100, &SimNode::onNodeWrench, this);
  fixed_nodes_sub_ = private_node.subscribe("fixed_nodes", 100, &SimNode::onFixedNodes, this);
  grasp_sub_ = private_node.subscribe("grasp", 100, &SimNode::onGrasp, this);
  grasp_srv_ = private_node.advertiseService("grasp", &SimNode::onSetGrasp, this);
  for (const core::Body& body : sim().bodies()) {
    reaction_pubs_.push_back(
        private_node.advertise<geometry_msgs::WrenchStamped>("reactions/" + body.name(), 10));
  }
  reset_srv_ = private_node.advertiseService("reset", &SimNode::onReset, this);
  pause_srv_ = private_node.advertiseService("pause", &SimNode::onPause, this);
  resume_srv_ = private_node.advertiseService("resume", &SimNode::onResume, this);
  step_srv_ = private_node.advertiseService("step", &SimNode::onStep, this);

  diagnostics_.setHardwareID("deformable_sim");
  diagnostics_.add("simulation", this, &SimNode::diagnose);

  // Live tuning: start from the scene's values so that the first callback changes nothing.
  const core::Body& first = sim().bodies().front();
  applied_config_.body = "";
  applied_config_.youngs_modulus = first.material().youngs_modulus;
  applied_config_.poisson_ratio = first.material().poisson_ratio;
  applied_config_.density = first.material().density;
  const core::RayleighDamping damping = first.effects().damping.value_or(core::RayleighDamping{});
  applied_config_.damping_mass = damping.mass;
  applied_config_.damping_stiffness = damping.stiffness;
  applied_config_.solver_tolerance = first.solverSettings().tolerance;
  applied_config_.solver_max_iterations = first.solverSettings().max_iterations;
  applied_config_.rate = rate_hz_;
  scene_config_ = applied_config_;
  reconfigure_ =
      std::make_unique<dynamic_reconfigure::Server<SimConfig>>(reconfigure_mutex_, private_node);
  SimConfig initial = applied_config_;
  reconfigure_->updateConfig(initial);
  reconfigure_->setCallback([this](SimConfig& config, uint32_t) { onReconfigure(config); });

  timer_ = node.createTimer(ros::Duration(1.0 / rate_hz_), &SimNode::onTimer, this);
  for (const core::Body& body : sim().bodies()) {
    std::string effects;
    for (const std::string& name : core::effectNames(body.effects(), body.model())) {
      effects += (effects.empty() ? "" : ", ") + name;
    }
    if (sim().contact() && body.model() == core::BodyModel::kFiniteElement) {
      effects += effects.empty() ? "contact" : ", contact";
    }
    ROS_INFO(
        "body '%s' (%s): %d nodes, %d tetrahedra, %zu other elements, %d fixed; frame '%s'; "
        "effects: %s",
        body.name().c_str(), core::modelName(body.model()), body.numNodes(),
        body.mesh().numTetrahedra(), body.mesh().cells.size(), body.numConstrained(),
        (frame_prefix_ + body.name()).c_str(), effects.empty() ? "none" : effects.c_str());
  }
  ROS_INFO("stepping %s at %.4g Hz x %d substeps (dt %.4g s) in frame '%s'",
           scene_path_.empty() ? "the built-in default scene" : scene_path_.c_str(), rate_hz_,
           substeps_, sim().dt(), world_frame_.c_str());
}

void SimNode::readParameters(ros::NodeHandle& private_node) {
  param(private_node, "scene", scene_path_);
  if (!scene_path_.empty()) {
    std::ifstream file(scene_path_);
    std::stringstream text;
    text << file.rdbuf();
    scene_text_ = text.str();
  }
  try {
    scene_ = scene_path_.empty() ? core::defaultScene() : io::readSceneFile(scene_path_);
  } catch (const io::SceneError& e) {
    throw std::runtime_error(std::string("~scene: ") + e.what());
  }
  world_frame_ = "world";
  param(private_node, "world_frame", world_frame_);
  world_frame_ = withoutLeadingSlash(world_frame_);
  // Several instances side by side: frames are prefixed by the node's namespace by default.
  std::string ns = withoutLeadingSlash(ros::this_node::getNamespace());
  frame_prefix_ = ns.empty() ? "" : ns + "/";
  param(private_node, "frame_prefix", frame_prefix_);
  frame_prefix_ = withoutLeadingSlash(frame_prefix_);
  param(private_node, "substeps", substeps_);
  if (substeps_ < 1) throw std::runtime_error("~substeps: must be >= 1");
  rate_hz_ = 1.0 / (scene_.dt * substeps_);
  param(private_node, "rate", rate_hz_);
  if (!(rate_hz_ > 0.0) || !std::isfinite(rate_hz_)) {
    throw std::runtime_error("~rate: must be finite and > 0 Hz");
  }
  scene_.dt = 1.0 / (rate_hz_ * substeps_);
  param(private_node, "start_paused", paused_);
  param(private_node, "wrench_timeout", wrench_timeout_s_);
  param(private_node, "stats_rate", stats_rate_hz_);
  param(private_node, "marker_rate", marker_rate_hz_);
  param(private_node, "strain_colour_scale", strain_colour_scale_);
  param(private_node, "max_force", limits_.max_force);
  param(private_node, "max_torque", limits_.max_torque);
  param(private_node, "max_target_distance", limits_.max_target_distance);
  if (!(wrench_timeout_s_ >= 0.0)) throw std::runtime_error("~wrench_timeout: must be >= 0 s");
  if (!(stats_rate_hz_ > 0.0)) throw std::runtime_error("~stats_rate: must be > 0 Hz");
  if (!(marker_rate_hz_ > 0.0)) throw std::runtime_error("~marker_rate: must be > 0 Hz");
  if (!(strain_colour_scale_ > 0.0)) throw std::runtime_error("~strain_colour_scale: must be > 0");
  if (!(limits_.max_force > 0.0) || !(limits_.max_torque > 0.0) ||
      !(limits_.max_target_distance > 0.0)) {
    throw std::runtime_error("~max_force, ~max_torque, ~max_target_distance: must be > 0");
  }
}

void SimNode::buildSimulation() {
  std::vector<std::string> warnings;
  std::vector<core::Mesh> meshes;
  try {
    meshes = io::readMeshes(scene_, &warnings);
    session_ = std::make_unique<core::Session>(scene_, meshes, limits_);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("~scene: ") + e.what());
  }
  for (const std::string& w : warnings) ROS_WARN("%s", w.c_str());
  session_->setListener([this](const core::AppliedCommand& applied) { publishApplied(applied); });
  for (const core::Body& body : sim().bodies())
    surfaces_.push_back(core::extractSurface(body.mesh()));
  clearTickState();
}

void SimNode::clearTickState() {
  wrench_times_.clear();
  grasp_frames_.clear();
  grasp_wrench_pubs_.clear();
  sim_time_samples_.clear();
  reports_.assign(sim().bodies().size(), core::StepReport{});
}

int SimNode::apply(const core::SessionCommand& command) {
  // Applied as recorded: the command read back from the very message published on ~applied, so
  // that a replay of it acts exactly as it did here (a pose's quaternion does not round-trip).
  recording_ = toMessage(command);
  return session_->apply(fromMessage(recording_));
}

void SimNode::publishApplied(const core::AppliedCommand& applied) {
  Applied& message = recording_;
  message.header.stamp = ros::Time::now();
  message.header.frame_id = world_frame_;
  message.episode = static_cast<uint64_t>(applied.episode);
  message.step = static_cast<uint64_t>(applied.step);
  applied_pub_.publish(message);
}

void SimNode::publishScene() {
  std::vector<std::string> names;
  for (const core::BodySpec& body : scene_.bodies) names.push_back(body.name);
  Scene message =
      toSceneMessage(scene_path_, scene_text_, sim().dt(), substeps_, session_->meshes(), names);
  message.header.stamp = ros::Time::now();
  message.header.frame_id = world_frame_;
  message.world_frame = world_frame_;
  message.frame_prefix = frame_prefix_;
  scene_pub_.publish(message);
}

std::string SimNode::bodyFrame(int body) const {
  return frame_prefix_ + sim().bodies()[body].name();
}

void SimNode::onTimer(const ros::TimerEvent&) {
  const ros::Time now = ros::Time::now();
  if (wrench_timeout_s_ > 0.0) {
    for (auto it = wrench_times_.begin(); it != wrench_times_.end();) {
      if ((now - it->second).toSec() > wrench_timeout_s_) {
        apply(core::ClearWrenchCommand{it->first});
        it = wrench_times_.erase(it);
      } else {
        ++it;
      }
    }
  }
  // A body must not fall through an obstacle that tf has not delivered yet: wait for them all.
  if (!updateObstacles()) {
    ROS_INFO_THROTTLE(2.0, "waiting for tf to place the obstacle links before stepping");
  } else if (!paused_) {
    advance(substeps_);
  }
  // Real-time factor over the last second of ROS time (the simulated clock with /use_sim_time).
  sim_time_samples_.emplace_back(now, sim().time());
  while (sim_time_samples_.size() > 2 && (now - sim_time_samples_.front().first).toSec() > 1.0) {
    sim_time_samples_.pop_front();
  }
  const double elapsed = (now - sim_time_samples_.front().first).toSec();
  real_time_factor_ =
      elapsed > 0.0 ? (sim().time() - sim_time_samples_.front().second) / elapsed : 0.0;

  publishState();
  publishFrames();
  publishGrasps();
  if (last_markers_.isZero() || (now - last_markers_).toSec() >= 1.0 / marker_rate_hz_ ||
      now < last_markers_) {
    publishMarkers();
    last_markers_ = now;
  }
  if (last_stats_.isZero() || (now - last_stats_).toSec() >= 1.0 / stats_rate_hz_ ||
      now < last_stats_) {
    publishStats();
    last_stats_ = now;
  }
  diagnostics_.update();
}

void SimNode::advance(int steps) {
  // Grasp frames move from where they were to where tf has them now, evenly over the substeps.
  std::vector<std::pair<std::string, std::pair<Eigen::Isometry3d, Eigen::Isometry3d>>> moves;
  for (const auto& [name, frame] : grasp_frames_) {
    moves.push_back({name, {session_->commands().grasps().at(name).frame, graspFramePose(name)}});
  }
  const ros::WallTime start = ros::WallTime::now();
  for (int s = 1; s <= steps; ++s) {
    const double t = static_cast<double>(s) / steps;
    for (const auto& [name, poses] : moves) {
      const auto& [from, to] = poses;
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.translation() = (1.0 - t) * from.translation() + t * to.translation();
      pose.linear() = Eigen::Quaterniond(from.linear())
                          .slerp(t, Eigen::Quaterniond(to.linear()))
                          .toRotationMatrix();
      apply(core::MoveGraspCommand{name, s == steps ? to : pose});
    }
    session_->step(reports_);
  }
  step_time_s_ = (ros::WallTime::now() - start).toSec();
  // The watchdog's recoveries (core::Simulation::step): counted, warned about, diagnosed.
  long recoveries = 0;
  for (size_t b = 0; b < sim().bodies().size(); ++b) {
    recoveries += sim().recoveries(static_cast<int>(b));
    if (reports_[b].recovered) {
      ROS_WARN_THROTTLE(1.0,
                        "body '%s': step %ld left a non-finite value; the watchdog restored the "
                        "last good positions and stopped the body",
                        sim().bodies()[b].name().c_str(), sim().stepCount());
    }
  }
  if (recoveries > recoveries_seen_) last_recovery_ = ros::WallTime::now();
  recoveries_seen_ = recoveries;  // a reset starts the count again
}

Eigen::Isometry3d SimNode::graspFramePose(const std::string& name) {
  const std::string& frame = grasp_frames_.at(name);
  try {
    const Eigen::Isometry3d pose =
        toEigen(tf_buffer_.lookupTransform(world_frame_, frame, ros::Time(0)).transform);
    if (pose.matrix().allFinite()) return pose;
  } catch (const tf2::TransformException& e) {
    ROS_WARN_THROTTLE(1.0, "grasp '%s': frame '%s' not in tf now (%s); holding its last pose",
                      name.c_str(), frame.c_str(), e.what());
  }
  return session_->commands().grasps().at(name).frame;
}

void SimNode::publishGrasps() {
  const ros::Time now = ros::Time::now();
  std::vector<geometry_msgs::TransformStamped> frames;
  for (const auto& [name, frame] : grasp_frames_) {
    const core::ActiveGrasp& grasp = session_->commands().grasps().at(name);
    const core::Wrench reaction = session_->commands().graspReaction(name);
    const Eigen::Matrix3d to_frame = grasp.frame.linear().transpose();
    geometry_msgs::WrenchStamped wrench;
    wrench.header.stamp = now;
    wrench.header.frame_id = frame;
    wrench.wrench.force = toVector3(to_frame * reaction.force);
    wrench.wrench.torque = toVector3(to_frame * reaction.torque);
    grasp_wrench_pubs_.at(name).publish(wrench);
    // The object seen from the gripper: how it slips or sags in the hand.
    const core::Body& body = sim().bodies()[grasp.body];
    geometry_msgs::TransformStamped object;
    object.header.stamp = now;
    object.header.frame_id = frame;
    object.child_frame_id = frame_prefix_ + name + "/object";
    object.transform = toTransform(
        grasp.frame.inverse() *
        toPose(core::bestFitFrame(body.positions(), body.restPositions(), body.nodalMasses())));
    frames.push_back(object);
  }
  if (!frames.empty()) tf_broadcaster_.sendTransform(frames);
  for (size_t b = 0; b < sim().bodies().size(); ++b) {
    if (reaction_pubs_[b].getNumSubscribers() == 0) continue;
    const core::Wrench reaction =
        session_->commands().fixedReaction(static_cast<int>(b), Eigen::Vector3d::Zero());
    geometry_msgs::WrenchStamped wrench;
    wrench.header.stamp = now;
    wrench.header.frame_id = world_frame_;
    wrench.wrench.force = toVector3(reaction.force);
    wrench.wrench.torque = toVector3(reaction.torque);
    reaction_pubs_[b].publish(wrench);
  }
}

bool SimNode::loadUrdf(std::string& error) {
  if (urdf_loaded_) return true;
  std::string xml;
  if (!scene_.urdf_file.empty()) {
    std::ifstream file(scene_.urdf_file);
    if (!file) {
      error = scene_.urdf_file + ": cannot open the URDF file";
      return false;
    }
    std::stringstream text;
    text << file.rdbuf();
    xml = text.str();
  } else if (!ros::NodeHandle().getParam("robot_description", xml) || xml.empty()) {
    error = "no robot description: set the robot_description parameter or the scene's urdf.file";
    return false;
  }
  std::vector<std::string> warnings;
  try {
    urdf_shapes_ = io::readCollisionShapes(xml, &warnings);
  } catch (const io::UrdfError& e) {
    error = e.what();
    return false;
  }
  for (const std::string& w : warnings) ROS_WARN("%s", w.c_str());
  urdf_loaded_ = true;
  return true;
}

bool SimNode::updateObstacles() {
  if (!sim().contact()) return true;
  std::vector<core::PlacedShape> obstacles = scene_.obstacles;  // these never move
  for (LinkObstacle& obstacle : link_obstacles_) {
    try {
      const Eigen::Isometry3d link =
          toEigen(tf_buffer_.lookupTransform(world_frame_, obstacle.link, ros::Time(0)).transform);
      if (link.matrix().allFinite()) {
        obstacle.placed = obstacle.local;
        obstacle.placed->pose = link * obstacle.local.pose;
      }
    } catch (const tf2::TransformException& e) {
      ROS_WARN_THROTTLE(5.0, "obstacle link '%s' is not in tf yet (%s)", obstacle.link.c_str(),
                        e.what());
    }
    if (obstacle.placed) obstacles.push_back(*obstacle.placed);
  }
  if (obstacles.size() != scene_.obstacles.size() + link_obstacles_.size()) return false;
  // Recorded (and applied) only when tf moved one.
  const auto same = [](const core::PlacedShape& a, const core::PlacedShape& b) {
    return a.name == b.name && a.shape.kind == b.shape.kind && a.shape.size == b.shape.size &&
           a.shape.radius == b.shape.radius && a.shape.length == b.shape.length &&
           a.pose.matrix() == b.pose.matrix();
  };
  if (!std::equal(obstacles.begin(), obstacles.end(), requested_obstacles_.begin(),
                  requested_obstacles_.end(), same)) {
    try {
      apply(core::SetObstaclesCommand{obstacles});
      requested_obstacles_ = std::move(obstacles);
    } catch (const core::CommandError& e) {
      ROS_WARN_THROTTLE(1.0, "obstacles not moved: %s", e.what());
    }
  }
  return true;
}

std::string SimNode::applyGrasp(const Grasp& message, uint32_t& nodes) {
  nodes = 0;
  if (message.action == Grasp::RELEASE) {
    const auto found = session_->commands().grasps().find(message.name);
    if (found == session_->commands().grasps().end())
      return "no grasp named '" + message.name + "'";
    nodes = static_cast<uint32_t>(found->second.nodes.size());
    apply(core::ReleaseGraspCommand{message.name});
    grasp_frames_.erase(message.name);
    grasp_wrench_pubs_.erase(message.name);  // its topic goes with it: names do not pile up
    return "";
  }
  if (message.action != Grasp::ATTACH) {
    return "action " + std::to_string(message.action) + " is neither ATTACH (0) nor RELEASE (1)";
  }
  const std::string frame = withoutLeadingSlash(message.header.frame_id);
  if (frame.empty())
    return "grasp '" + message.name + "': header.frame_id is empty: name the frame to follow";
  FrameTarget target;
  std::string error;
  if (!resolveFrame(frame, target, error)) return "grasp '" + message.name + "': " + error;
  if (target.body >= 0 || frame == world_frame_) {
    return "grasp '" + message.name + "': '" + frame +
           "' is not a tf frame that can hold a body (it is the world or one of this node's "
           "frames)";
  }
  core::GraspCommand command;
  command.name = message.name;
  command.body = message.body;
  command.frame = target.pose;
  command.nodes.region_pose = target.pose;
  switch (message.region) {
    case Grasp::REGION_BOX:
      command.nodes.box = core::Box{toEigen(message.box_min), toEigen(message.box_max)};
      break;
    case Grasp::REGION_SPHERE:
      command.nodes.sphere = core::Sphere{toEigen(message.sphere_center), message.sphere_radius};
      break;
    case Grasp::REGION_LINK: {
      const std::string link = message.link.empty() ? frame : message.link;
      FrameTarget link_frame;
      if (!loadUrdf(error) || !resolveFrame(link, link_frame, error)) {
        return "grasp '" + message.name + "': link '" + link + "': " + error;
      }
      try {
        for (core::PlacedShape shape : io::linkShapes(urdf_shapes_, link)) {
          shape.pose = link_frame.pose * shape.pose;
          command.nodes.shapes.push_back(shape);
        }
      } catch (const io::UrdfError& e) {
        return "grasp '" + message.name + "': " + e.what();
      }
      command.nodes.shape_margin = message.margin;
      break;
    }
    default:
      return "grasp '" + message.name + "': region " + std::to_string(message.region) +
             " is not REGION_BOX, REGION_SPHERE or REGION_LINK";
  }
  try {
    nodes = static_cast<uint32_t>(apply(command));
  } catch (const core::CommandError& e) {
    return e.what();
  }
  grasp_frames_[message.name] = frame;
  if (grasp_wrench_pubs_.count(message.name) == 0) {
    grasp_wrench_pubs_[message.name] = private_node_.advertise<geometry_msgs::WrenchStamped>(
        "grasps/" + message.name + "/wrench", 10);
  }
  return "";
}

void SimNode::onGrasp(const Grasp::ConstPtr& message) {
  uint32_t nodes = 0;
  const std::string error = applyGrasp(*message, nodes);
  if (!error.empty()) refuse("~grasp", error);
}

bool SimNode::onSetGrasp(SetGrasp::Request& request, SetGrasp::Response& response) {
  const std::string error = applyGrasp(request.grasp, response.nodes);
  response.success = error.empty();
  response.message = error.empty()
                         ? (request.grasp.action == Grasp::ATTACH ? "attached " : "released ") +
                               std::to_string(response.nodes) + " nodes"
                         : error;
  if (!error.empty()) refuse("~grasp (service)", error);
  return true;
}

void SimNode::publishState() {
  const ros::Time now = ros::Time::now();
  for (const core::Body& body : sim().bodies()) {
    fillState(body, state_message_);
    state_message_.header.stamp = now;
    state_message_.header.frame_id = world_frame_;
    state_message_.episode = static_cast<uint64_t>(session_->episode());
    state_message_.step = static_cast<uint64_t>(sim().stepCount());
    state_pub_.publish(state_message_);
  }
}

void SimNode::publishFrames() {
  tf_broadcaster_.sendTransform(
      bodyFrames(sim().bodies(), world_frame_, frame_prefix_, ros::Time::now()));
}

void SimNode::publishMarkers() {
  std_msgs::Header header;
  header.stamp = ros::Time::now();
  header.frame_id = world_frame_;
  if (mesh_pub_.getNumSubscribers() > 0) {
    for (const core::Body& body : sim().bodies()) {
      const bool colour = body.effects().stress_colouring;
      if (colour) core::nodalStrain(body, strain_);
      const size_t b = &body - sim().bodies().data();
      fillSurfaceMarker(body, surfaces_[b], colour ? &strain_ : nullptr, strain_colour_scale_,
                        mesh_message_);
      mesh_message_.header = header;
      mesh_pub_.publish(mesh_message_);
    }
  }
  if (markers_pub_.getNumSubscribers() > 0) {
    markers_pub_.publish(interactionMarkers(sim().bodies(), session_->commands(), header));
  }
}

void SimNode::publishStats() {
  Stats stats;
  stats.header.stamp = ros::Time::now();
  stats.header.frame_id = world_frame_;
  stats.step = static_cast<uint64_t>(sim().stepCount());
  stats.sim_time = sim().time();
  stats.paused = paused_;
  stats.step_time = step_time_s_;
  stats.real_time_factor = real_time_factor_;
  stats.dropped_messages = refusals_.count();
  stats.last_refusal = refusals_.last();
  for (size_t b = 0; b < sim().bodies().size(); ++b) {
    const core::Body& body = sim().bodies()[b];
    BodyStats s;
    s.body = body.name();
    s.model = core::modelName(body.model());
    s.effects = core::effectNames(body.effects(), body.model());
    if (sim().contact() && body.model() == core::BodyModel::kFiniteElement) {
      s.effects.emplace_back("contact");
    }
    s.solver_iterations = static_cast<uint32_t>(reports_[b].solve.iterations);
    s.solves = static_cast<uint32_t>(reports_[b].solves);
    s.splits = static_cast<uint32_t>(reports_[b].splits);
    s.solver_residual = reports_[b].solve.relative_residual;
    s.solver_converged = reports_[b].solve.converged;
    s.kinetic_energy = body.kineticEnergy();
    s.elastic_energy = body.elasticEnergy();
    s.inverted_elements = static_cast<uint32_t>(reports_[b].inverted_elements);
    s.fixed_nodes = static_cast<uint32_t>(body.numConstrained());
    s.contacts = static_cast<uint32_t>(reports_[b].contacts);
    s.recovered = reports_[b].recovered;
    s.recoveries = static_cast<uint32_t>(sim().recoveries(static_cast<int>(b)));
    for (const auto& [name, grasp] : session_->commands().grasps()) {
      if (grasp.body == static_cast<int>(b)) s.grasped_nodes += grasp.nodes.size();
    }
    for (const auto& [source, wrench] : session_->commands().activeWrenches()) {
      s.applied_wrenches += wrench.body == static_cast<int>(b) ? 1 : 0;
    }
    stats.bodies.push_back(s);
  }
  stats_pub_.publish(stats);
}

bool SimNode::resolveFrame(const std::string& frame_id, FrameTarget& target,
                           std::string& error) const {
  const std::string frame = withoutLeadingSlash(frame_id);
  target = FrameTarget{};
  if (frame.empty() || frame == world_frame_) return true;
  std::string own;
  for (size_t b = 0; b < sim().bodies().size(); ++b) {
    const core::Body& body = sim().bodies()[b];
    const std::string name = bodyFrame(static_cast<int>(b));
    own += (own.empty() ? "" : ", ") + name;
    if (frame == name) {
      target.body = static_cast<int>(b);
      target.pose =
          toPose(core::bestFitFrame(body.positions(), body.restPositions(), body.nodalMasses()));
      return true;
    }
    if (frame.rfind(name + "/", 0) == 0) {
      const std::string group = frame.substr(name.size() + 1);
      const auto found = body.groups().find(group);
      if (found == body.groups().end()) {
        std::string groups;
        for (const auto& [g, nodes] : body.groups()) groups += (groups.empty() ? "" : ", ") + g;
        error = "frame '" + frame + "': body '" + body.name() + "' has no group '" + group + "'" +
                (groups.empty() ? "" : " (groups: " + groups + ")");
        return false;
      }
      target.body = static_cast<int>(b);
      target.group = group;
      target.pose = toPose(core::bestFitFrame(body.positions(), body.restPositions(),
                                              body.nodalMasses(), found->second));
      return true;
    }
  }
  try {
    target.pose = toEigen(tf_buffer_.lookupTransform(world_frame_, frame, ros::Time(0)).transform);
  } catch (const tf2::TransformException& e) {
    error = "unknown frame '" + frame + "': not a body or group frame of this node (" + own +
            ", and their groups) and not in tf (" + e.what() + ")";
    return false;
  }
  if (!target.pose.matrix().allFinite()) {
    error = "frame '" + frame + "' has a non-finite pose in tf";
    return false;
  }
  return true;
}

void SimNode::refuse(const std::string& topic, const std::string& reason) {
  const std::string warning = refusals_.refuse(topic, reason, ros::WallTime::now());
  if (!warning.empty()) ROS_WARN("%s", warning.c_str());
}

void SimNode::onWrench(const geometry_msgs::WrenchStamped::ConstPtr& message) {
  const std::string topic = "~wrench";
  const std::string frame = withoutLeadingSlash(message->header.frame_id);
  if (frame.empty()) {
    return refuse(topic,
                  "header.frame_id is empty: name a body, a node group (<body>/<group>) "
                  "or a tf frame");
  }
  core::WrenchCommand command;
  command.source = frame;
  const Eigen::Vector3d force = toEigen(message->wrench.force);
  const Eigen::Vector3d torque = toEigen(message->wrench.torque);
  // A zero wrench removes the frame's wrench without resolving the frame (it may have left tf);
  // one that removes nothing must name a frame a wrench could act on, like any other wrench.
  const bool clears = force.isZero(0.0) && torque.isZero(0.0) &&
                      session_->commands().activeWrenches().count(frame) > 0;
  if (!clears) {
    FrameTarget target;
    std::string error;
    if (!resolveFrame(frame, target, error)) return refuse(topic, error);
    command.force = target.pose.linear() * force;
    command.torque = target.pose.linear() * torque;
    command.point = target.pose.translation();
    if (target.body >= 0) {
      command.body = sim().bodies()[target.body].name();
      command.nodes.group = target.group;
      command.nodes.whole_body = target.group.empty();
    } else {
      // Another tf frame: the nodes of the nearest body within its wrench_radius of the origin.
      int nearest = 0;
      double best = std::numeric_limits<double>::infinity();
      for (size_t b = 0; b < sim().bodies().size(); ++b) {
        const Eigen::VectorXd& x = sim().bodies()[b].positions();
        for (int i = 0; i < sim().bodies()[b].numNodes(); ++i) {
          const double d = (x.segment<3>(3 * i) - *command.point).norm();
          if (d < best) best = d, nearest = static_cast<int>(b);
        }
      }
      command.body = sim().bodies()[nearest].name();
      command.nodes.sphere = core::Sphere{*command.point, sim().wrenchRadius(nearest)};
    }
  } else {
    command.force = force;  // zero (or -0): clears the wrench of this frame
    command.torque = torque;
  }
  try {
    apply(command);
  } catch (const core::CommandError& e) {
    return refuse(topic, "frame '" + frame + "': " + e.what());
  }
  if (command.force.isZero(0.0) && command.torque.isZero(0.0)) {
    wrench_times_.erase(frame);
  } else {
    wrench_times_[frame] = ros::Time::now();
  }
}

void SimNode::onNodeWrench(const NodeWrench::ConstPtr& message) {
  const std::string topic = "~node_wrench";
  FrameTarget frame;
  std::string error;
  if (!resolveFrame(message->header.frame_id, frame, error)) return refuse(topic, error);
  try {
    const core::WrenchCommand command = toCommand(*message, frame.pose);
    apply(command);
    if (command.force.isZero(0.0) && command.torque.isZero(0.0)) {
      wrench_times_.erase(command.source);
    } else {
      wrench_times_[command.source] = ros::Time::now();
    }
  } catch (const core::CommandError& e) {
    refuse(topic, e.what());
  }
}

void SimNode::onFixedNodes(const FixedNodes::ConstPtr& message) {
  const std::string topic = "~fixed_nodes";
  FrameTarget frame;
  std::string error;
  if (!resolveFrame(message->header.frame_id, frame, error)) return refuse(topic, error);
  try {
    apply(toCommand(*message, frame.pose));
  } catch (const core::CommandError& e) {
    refuse(topic, e.what());
  }
}

bool SimNode::onReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  apply(core::ResetCommand{});
  clearTickState();
  requested_obstacles_.clear();
  // Keep what was tuned live: re-apply what differs from the scene's own values.
  SimConfig tuned = applied_config_;
  applied_config_ = scene_config_;
  applied_config_.body = tuned.body;
  onReconfigure(tuned);
  publishState();
  publishFrames();
  response.success = true;
  response.message = "reset to the scene's initial state";
  return true;
}

bool SimNode::onPause(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  response.success = true;
  response.message =
      paused_ ? "already paused" : "paused at step " + std::to_string(sim().stepCount());
  paused_ = true;
  return true;
}

bool SimNode::onResume(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  response.success = true;
  response.message =
      paused_ ? "resumed at step " + std::to_string(sim().stepCount()) : "not paused";
  paused_ = false;
  return true;
}

bool SimNode::onStep(Step::Request& request, Step::Response& response) {
  if (!paused_) {
    response.success = false;
    response.message = "not paused: call ~pause first";
  } else if (!updateObstacles()) {
    response.success = false;
    response.message = "waiting for tf to place the obstacle links";
  } else {
    advance(static_cast<int>(request.steps));
    publishState();
    publishFrames();
    publishGrasps();
    response.success = true;
    response.message = "took " + std::to_string(request.steps) + " steps";
  }
  response.step = static_cast<uint64_t>(sim().stepCount());
  return true;
}

void SimNode::onReconfigure(SimConfig& config) {
  const SimConfig before = applied_config_;
  std::vector<core::TuneCommand> tunes;
  for (const core::Body& body : sim().bodies()) {
    if (!config.body.empty() && body.name() != config.body) continue;
    core::TuneCommand tune;
    tune.body = body.name();
    if (config.youngs_modulus != before.youngs_modulus ||
        config.poisson_ratio != before.poisson_ratio || config.density != before.density) {
      core::LinearElasticMaterial material = body.material();
      if (config.youngs_modulus != before.youngs_modulus)
        material.youngs_modulus = config.youngs_modulus;
      if (config.poisson_ratio != before.poisson_ratio)
        material.poisson_ratio = config.poisson_ratio;
      if (config.density != before.density) material.density = config.density;
      tune.material = material;
    }
    if (config.damping_mass != before.damping_mass ||
        config.damping_stiffness != before.damping_stiffness) {
      tune.damping = core::RayleighDamping{config.damping_mass, config.damping_stiffness};
    }
    if (config.solver_tolerance != before.solver_tolerance) {
      tune.solver_tolerance = config.solver_tolerance;
    }
    if (config.solver_max_iterations != before.solver_max_iterations) {
      tune.solver_max_iterations = config.solver_max_iterations;
    }
    if (tune.material || tune.damping || tune.solver_tolerance || tune.solver_max_iterations) {
      tunes.push_back(tune);
    }
  }
  if (tunes.empty() && !config.body.empty() && sim().bodyIndex(config.body) < 0) {
    refuse("~set_parameters", "no body named '" + config.body + "'; nothing changed");
    config = before;
    return;
  }
  if (config.rate != before.rate) {
    core::TuneCommand tune;
    tune.dt = 1.0 / (config.rate * substeps_);
    tunes.push_back(tune);
  }
  try {
    for (const core::TuneCommand& tune : tunes) apply(tune);
  } catch (const core::CommandError& e) {
    refuse("~set_parameters", e.what());
    config = before;
    return;
  }
  if (config.rate != before.rate) {
    rate_hz_ = config.rate;
    if (timer_.isValid()) timer_.setPeriod(ros::Duration(1.0 / rate_hz_));
  }
  applied_config_ = config;
}

void SimNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  bool converged = true;
  int inverted = 0;
  for (const core::StepReport& r : reports_) {
    converged = converged && r.solve.converged;
    inverted += r.inverted_elements;
  }
  if (!last_recovery_.isZero() && (ros::WallTime::now() - last_recovery_).toSec() < 2.0) {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN,
                   "the watchdog undid a step that left a non-finite value");
  } else if (!converged) {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "a solve did not reach its tolerance");
  } else if (!paused_ && real_time_factor_ < 0.9 && sim().stepCount() > 10 * substeps_) {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "cannot keep real time");
  } else {
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, paused_ ? "paused" : "running");
  }
  status.add("step", sim().stepCount());
  status.add("simulated time (s)", sim().time());
  status.add("real-time factor", real_time_factor_);
  status.add("step time (ms)", 1e3 * step_time_s_);
  status.add("inverted elements", inverted);
  status.add("watchdog recoveries", recoveries_seen_);
  status.add("dropped messages", refusals_.count());
  status.add("last refusal", refusals_.last());
}

}  // namespace deformable_sim::ros_layer
