#include "deformable_sim/ros/node_outputs.h"

#include <algorithm>

#include "deformable_sim/Stats.h"
#include "deformable_sim/core/outputs/body_activity.h"
#include "deformable_sim/core/outputs/body_colours.h"
#include "deformable_sim/ros/body_frames.h"
#include "deformable_sim/ros/conversions.h"

namespace deformable_sim::ros_layer {

namespace {

visualization_msgs::MarkerArray deleteAllArray() {
  visualization_msgs::MarkerArray array;
  array.markers.push_back(deleteAllMarker());
  return array;
}

/// Wall time of one tick's substeps, s: a late callback steps the ticks it missed as well.
double tickTime(const TickStatus& status, int substeps) {
  return status.steps > 0 ? status.step_time_s * substeps / status.steps : 0.0;
}

// How long rviz keeps a body's mesh not sent again: ten marker periods, and at least 10 s so that
// slow ticks (a real-time factor of 0.01 makes a 30 Hz tick last 3.3 s) do not blank it. The
// meshes of an earlier run of the node that died without clearing them vanish after that, with
// no DELETEALL on ~mesh before the first mesh.
double meshLifetime(double marker_rate_hz) { return std::max(10.0, 10.0 / marker_rate_hz); }

}  // namespace

NodeOutputs::NodeOutputs(ros::NodeHandle& node, ros::NodeHandle& private_node,
                         const NodeParameters& params, const core::Session& session)
    : params_(params),
      diagnostics_(node, private_node),
      marker_schedule_(1.0 / params.marker_rate_hz),
      stats_schedule_(1.0 / params.stats_rate_hz),
      surfaces_(session.simulation(), params.strain_colour_scale, core::bodyColours(params.scene),
                meshLifetime(params.marker_rate_hz)) {
  state_pub_ = private_node.advertise<BodyState>("state", 10);
  stats_pub_ = private_node.advertise<Stats>("stats", 10);
  mesh_pub_ = private_node.advertise<visualization_msgs::Marker>("mesh", 2);
  markers_pub_ = private_node.advertise<visualization_msgs::MarkerArray>("markers", 2);
  for (const core::Body& body : session.simulation().bodies()) {
    reaction_pubs_.push_back(
        private_node.advertise<geometry_msgs::WrenchStamped>("reactions/" + body.name(), 10));
  }
  diagnostics_.setHardwareID("deformable_sim");
  diagnostics_.add("simulation", this, &NodeOutputs::diagnose);
}

bool NodeOutputs::publishState(const core::Session& session, const ros::Time& stamp) {
  const core::Simulation& sim = session.simulation();
  for (const core::Body& body : sim.bodies()) {
    fillState(body, state_message_);
    state_message_.header.stamp = stamp;
    state_message_.header.frame_id = params_.world_frame;
    state_message_.episode = static_cast<uint64_t>(session.episode());
    state_message_.step = static_cast<uint64_t>(sim.stepCount());
    state_pub_.publish(state_message_);
  }
  const bool send_tf = tf_stamps_.accept(static_cast<int64_t>(stamp.toNSec()));
  if (send_tf) {
    broadcaster_.sendTransform(
        bodyFrames(sim.bodies(), params_.world_frame, params_.frame_prefix, stamp));
  }
  for (size_t b = 0; b < sim.bodies().size(); ++b) {
    if (reaction_pubs_[b].getNumSubscribers() == 0) continue;
    const core::Wrench reaction =
        session.commands().fixedReaction(static_cast<int>(b), Eigen::Vector3d::Zero());
    reaction_pubs_[b].publish(
        toMessage(reaction, params_.world_frame, Eigen::Isometry3d::Identity(), stamp));
  }
  return send_tf;
}

void NodeOutputs::publishPeriodic(const core::Session& session, const TickStatus& status,
                                  const core::RefusalLog& refusals, const ros::Time& now,
                                  const ros::Time& stamp) {
  if (marker_schedule_.due(now.toSec())) {
    std_msgs::Header header;
    header.stamp = stamp;
    header.frame_id = params_.world_frame;
    publishMarkers(session, header);
  }
  if (stats_schedule_.due(now.toSec())) publishStats(session, status, refusals, stamp);
  session_ = &session;
  status_ = &status;
  refusals_ = &refusals;
  diagnostics_.update();
}

void NodeOutputs::clearMarkers() {
  mesh_pub_.publish(deleteAllMarker());
  markers_pub_.publish(deleteAllArray());
}

void NodeOutputs::publishMarkers(const core::Session& session, const std_msgs::Header& header) {
  const core::BodyList& bodies = session.simulation().bodies();
  if (mesh_pub_.getNumSubscribers() > 0) {
    for (size_t b = 0; b < bodies.size(); ++b) {
      mesh_pub_.publish(surfaces_.marker(bodies[b], static_cast<int>(b), header));
    }
  }
  if (markers_pub_.getNumSubscribers() > 0) {
    visualization_msgs::MarkerArray array = interactionMarkers(bodies, session.commands(), header);
    if (session.simulation().contact()) {
      core::touchingPairs(session.simulation(), contact_pairs_);
      appendContactMarkers(contact_pairs_, header, array);
    }
    markers_pub_.publish(array);
  }
}

void NodeOutputs::publishStats(const core::Session& session, const TickStatus& status,
                               const core::RefusalLog& refusals, const ros::Time& stamp) {
  const core::Simulation& sim = session.simulation();
  Stats stats;
  stats.header.stamp = stamp;
  stats.header.frame_id = params_.world_frame;
  stats.step = static_cast<uint64_t>(sim.stepCount());
  stats.sim_time = sim.time();
  stats.paused = status.paused;
  stats.step_time = tickTime(status, params_.substeps);
  stats.real_time_factor = status.real_time_factor;
  stats.dropped_messages = refusals.count();
  stats.last_refusal = refusals.last();
  for (size_t b = 0; b < sim.bodies().size(); ++b) {
    const core::Body& body = sim.bodies()[b];
    const core::StepReport& report = status.reports[b];
    const int index = static_cast<int>(b);
    BodyStats s;
    s.body = body.name();
    s.model = core::modelName(body.settings().model);
    s.effects = core::activeEffects(sim, index);
    s.elasticity_time = report.times.rotations + report.times.assembly;
    s.solve_time = report.times.solve;
    s.contact_time = report.times.obstacle_contact + report.times.body_contact;
    s.solver_iterations = static_cast<uint32_t>(report.solve.iterations);
    s.solves = static_cast<uint32_t>(report.solves);
    s.splits = static_cast<uint32_t>(report.splits);
    s.solver_residual = report.solve.relative_residual;
    s.solver_converged = report.solve.converged;
    s.kinetic_energy = body.kineticEnergy();
    s.elastic_energy = body.elasticEnergy();
    s.inverted_elements = static_cast<uint32_t>(report.inverted_elements);
    s.fixed_nodes = static_cast<uint32_t>(numConstrained(body));
    s.contacts = static_cast<uint32_t>(report.contacts);
    s.body_contacts = static_cast<uint32_t>(report.body_contacts);
    s.self_contacts = static_cast<uint32_t>(report.self_contacts);
    s.recovered = report.recovered;
    s.recoveries = static_cast<uint32_t>(sim.recoveries(index));
    s.grasped_nodes = static_cast<uint32_t>(core::graspedNodes(session.commands(), index));
    s.applied_wrenches = static_cast<uint32_t>(core::appliedWrenches(session.commands(), index));
    stats.bodies.push_back(s);
  }
  stats_pub_.publish(stats);
}

void NodeOutputs::diagnose(diagnostic_updater::DiagnosticStatusWrapper& out) {
  if (!session_) return;
  const core::Simulation& sim = session_->simulation();
  const core::Health health = core::health(*status_);
  using Status = diagnostic_msgs::DiagnosticStatus;
  out.summary(health.ok ? Status::OK : Status::WARN, health.summary);
  out.add("step", sim.stepCount());
  out.add("simulated time (s)", sim.time());
  out.add("real-time factor", status_->real_time_factor);
  out.add("step time (ms)", 1e3 * tickTime(*status_, params_.substeps));
  out.add("inverted elements", health.inverted_elements);
  out.add("watchdog recoveries", status_->recoveries);
  out.add("dropped messages", refusals_->count());
  out.add("last refusal", refusals_->last());
}

}  // namespace deformable_sim::ros_layer
