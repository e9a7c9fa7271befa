#include "deformable_sim/ros/measured_bag.h"

#include <geometry_msgs/WrenchStamped.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <tf2/buffer_core.h>
#include <tf2/exceptions.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_msgs/TFMessage.h>

#include <set>

namespace deformable_sim::ros_layer {

namespace {

using identify::FitSpecError;
using identify::ObservationSpec;

// Every transform of /tf and /tf_static, for the sensors' frames.
void fillBuffer(const rosbag::Bag& bag, tf2::BufferCore& buffer) {
  for (const rosbag::MessageInstance& m :
       rosbag::View(bag, rosbag::TopicQuery(std::vector<std::string>{"/tf", "/tf_static"}))) {
    const tf2_msgs::TFMessage::ConstPtr message = m.instantiate<tf2_msgs::TFMessage>();
    if (!message) continue;
    for (const geometry_msgs::TransformStamped& t : message->transforms)
      buffer.setTransform(t, "bag", m.getTopic() == "/tf_static");
  }
}

void readFrame(const rosbag::Bag& bag, const ObservationSpec& spec, const std::string& world,
               const identify::SessionClock& clock, identify::MeasuredSeries& series,
               long& outside) {
  bool seen = false;
  for (const rosbag::MessageInstance& m :
       rosbag::View(bag, rosbag::TopicQuery(std::string("/tf")))) {
    const tf2_msgs::TFMessage::ConstPtr message = m.instantiate<tf2_msgs::TFMessage>();
    if (!message) continue;
    for (const geometry_msgs::TransformStamped& t : message->transforms) {
      if (t.child_frame_id != spec.topic) continue;
      seen = true;
      if (t.header.frame_id != world && t.header.frame_id != "/" + world) {
        throw FitSpecError(spec.key + ".tf: frame '" + spec.topic + "' is a child of '" +
                           t.header.frame_id + "', not of the world frame '" + world + "'");
      }
      const std::optional<double> time = clock.timeAt(t.header.stamp.toNSec());
      if (!time) {
        ++outside;
        continue;
      }
      series.times.push_back(*time);
      const geometry_msgs::Vector3& p = t.transform.translation;
      series.values.push_back(Eigen::Vector3d(p.x, p.y, p.z));
    }
  }
  if (!seen) throw FitSpecError(spec.key + ".tf: the bag's /tf has no frame '" + spec.topic + "'");
}

std::string withoutSlash(const std::string& frame) {
  return !frame.empty() && frame[0] == '/' ? frame.substr(1) : frame;
}

Eigen::Isometry3d sensorFrame(const tf2::BufferCore& buffer, const ObservationSpec& spec,
                              const std::string& frame, const std::string& world,
                              const ros::Time& stamp) {
  if (frame.empty() || frame == world || frame == "/" + world) return Eigen::Isometry3d::Identity();
  try {
    return tf2::transformToEigen(buffer.lookupTransform(world, frame, stamp));
  } catch (const tf2::TransformException& e) {
    throw FitSpecError(spec.key + ".wrench: its frame '" + frame +
                       "' is not in the bag's tf: " + e.what());
  }
}

void readWrench(const rosbag::Bag& bag, const ObservationSpec& spec, const std::string& world,
                const identify::SessionClock& clock, const tf2::BufferCore& buffer,
                identify::MeasuredSeries& series, Eigen::Isometry3d& frame, long& outside) {
  rosbag::View view(bag, rosbag::TopicQuery(spec.topic));
  if (view.size() == 0)
    throw FitSpecError(spec.key + ".wrench: the bag has no topic '" + spec.topic + "'");
  bool first = true;
  for (const rosbag::MessageInstance& m : view) {
    const geometry_msgs::WrenchStamped::ConstPtr w = m.instantiate<geometry_msgs::WrenchStamped>();
    if (!w) {
      throw FitSpecError(spec.key + ".wrench: '" + spec.topic + "' is a " + m.getDataType() +
                         ", not a geometry_msgs/WrenchStamped");
    }
    if (first) frame = sensorFrame(buffer, spec, w->header.frame_id, world, w->header.stamp);
    first = false;
    const bool moves = !w->header.frame_id.empty() && withoutSlash(w->header.frame_id) != world;
    const std::optional<double> time = clock.timeAt(w->header.stamp.toNSec());
    if (!time) {
      ++outside;
      continue;
    }
    series.times.push_back(*time);
    // Its frame where it was at this sample (a sensor on a moving link; a fixed one stays put).
    if (moves) {
      series.frames.push_back(
          sensorFrame(buffer, spec, w->header.frame_id, world, w->header.stamp));
    }
    Eigen::VectorXd value(6);
    value << w->wrench.force.x, w->wrench.force.y, w->wrench.force.z, w->wrench.torque.x,
        w->wrench.torque.y, w->wrench.torque.z;
    series.values.push_back(value);
  }
}

}  // namespace

Measurements readMeasurements(const std::string& path,
                              const std::vector<ObservationSpec>& observations,
                              const std::string& world_frame, const identify::SessionClock& clock) {
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  tf2::BufferCore buffer(ros::Duration(1.0e6));
  fillBuffer(bag, buffer);
  Measurements result;
  result.series.resize(observations.size());
  result.sensor_frames.assign(observations.size(), Eigen::Isometry3d::Identity());
  result.outside.assign(observations.size(), 0);
  for (std::size_t o = 0; o < observations.size(); ++o) {
    const ObservationSpec& spec = observations[o];
    if (spec.kind == ObservationSpec::Kind::kFrame) {
      readFrame(bag, spec, world_frame, clock, result.series[o], result.outside[o]);
    } else {
      readWrench(bag, spec, world_frame, clock, buffer, result.series[o], result.sensor_frames[o],
                 result.outside[o]);
    }
  }
  return result;
}

}  // namespace deformable_sim::ros_layer
