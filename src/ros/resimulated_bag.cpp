#include "deformable_sim/ros/resimulated_bag.h"

#include <rosbag/exceptions.h>
#include <tf2_msgs/TFMessage.h>

#include <utility>

#include "deformable_sim/ros/body_frames.h"
#include "deformable_sim/ros/conversions.h"
#include "deformable_sim/ros/markers.h"
#include "deformable_sim/ros/replay.h"

namespace deformable_sim::ros_layer {

namespace {

// A bag cannot hold time zero: a header without a stamp goes first.
ros::Time bagTime(const ros::Time& stamp) { return stamp.isZero() ? ros::TIME_MIN : stamp; }

}  // namespace

ResimulatedBag::ResimulatedBag(const std::string& path, const std::string& node, const Scene& scene,
                               const core::Simulation& simulation,
                               const std::vector<std_msgs::Header>& state_headers,
                               double marker_rate, std::vector<Eigen::Vector3d> colours)
    : node_(node),
      scene_(scene),
      state_headers_(state_headers),
      marker_period_(1.0 / marker_rate),
      marker_schedule_(marker_period_),
      surfaces_(simulation, kDefaultStrainScale, std::move(colours)) {
  try {
    bag_.open(path, rosbag::bagmode::Write);
  } catch (const rosbag::BagException& e) {
    throw ReplayError(path + ": cannot write: " + e.what());
  }
}

void ResimulatedBag::write(const core::ComparedState& state) {
  const std_msgs::Header& header = state_headers_[state.recorded.source];
  const ros::Time stamp = bagTime(header.stamp);
  // At the first state, not at the scene's own stamp (when the node started, which may be long
  // before): the bag then starts where its states do.
  if (!scene_written_) writeScene(stamp);
  const core::Body& body = state.simulation.bodies()[state.body];
  fillState(body, state_message_);
  state_message_.header = header;
  state_message_.episode = static_cast<uint64_t>(state.episode);
  state_message_.step = static_cast<uint64_t>(state.step);
  bag_.write(node_ + "/state", stamp, state_message_);
  if (state.body == 0) writeFrames(state, stamp);
  if (markerDue(state)) writeSurface(state, header);
}

void ResimulatedBag::close() {
  if (!scene_written_) writeScene(bagTime(scene_.header.stamp));
  bag_.close();
}

void ResimulatedBag::writeScene(const ros::Time& stamp) {
  bag_.write(node_ + "/scene", stamp, scene_);
  scene_written_ = true;
}

void ResimulatedBag::writeFrames(const core::ComparedState& state, const ros::Time& stamp) {
  // States recorded under a coarse simulated clock may share a stamp: tf would warn.
  if (!tf_stamps_.accept(static_cast<int64_t>(stamp.toNSec()))) return;
  tf2_msgs::TFMessage tf;
  tf.transforms =
      bodyFrames(state.simulation.bodies(), scene_.world_frame, scene_.frame_prefix, stamp);
  bag_.write("/tf", stamp, tf);
}

void ResimulatedBag::writeSurface(const core::ComparedState& state,
                                  const std_msgs::Header& header) {
  const core::Body& body = state.simulation.bodies()[state.body];
  bag_.write(node_ + "/mesh", bagTime(header.stamp), surfaces_.marker(body, state.body, header));
}

// Every body's surface at the marker rate of simulated time (counted from the last time due, not
// from the state: states at 100 Hz must give markers at 30 Hz, not 25), and at an episode's start.
bool ResimulatedBag::markerDue(const core::ComparedState& state) {
  if (state.episode == last_episode_ && state.step == last_step_) return marker_due_;
  if (state.episode != last_episode_) marker_schedule_ = core::PeriodicSchedule(marker_period_);
  marker_due_ = marker_schedule_.due(state.simulation.time());
  last_episode_ = state.episode;
  last_step_ = state.step;
  return marker_due_;
}

}  // namespace deformable_sim::ros_layer
