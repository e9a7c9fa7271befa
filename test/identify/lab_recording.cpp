#include "lab_recording.h"

#include <geometry_msgs/WrenchStamped.h>
#include <rosbag/bag.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_msgs/TFMessage.h>

#include <limits>
#include <random>

#include "deformable_sim/core/outputs/contact_pairs.h"
#include "deformable_sim/core/outputs/mesh_catalogue.h"
#include "deformable_sim/io/scene_file.h"
#include "deformable_sim/ros/session_messages.h"

namespace deformable_sim::test {

namespace {

const ros::Time kStart(1000.0);
const char* kWorld = "world";

struct Truth {
  std::vector<std::vector<Eigen::Vector3d>> markers;  ///< per step, per marker
  std::vector<Eigen::Matrix<double, 6, 1>> wrench;    ///< per step
};

int nodeAt(const core::Body& body, const Eigen::Vector3d& at) {
  for (int i = 0; i < body.numNodes(); ++i) {
    if ((body.restPositions().segment<3>(3 * i) - at).norm() < 1e-9) return i;
  }
  throw std::invalid_argument("no mesh node at the marker's rest position");
}

void recordStep(const LabRecording& lab, const core::Session& session,
                const std::vector<int>& nodes, Truth& truth) {
  const core::Simulation& sim = session.simulation();
  const int b = sim.bodyIndex(lab.body);
  const core::Body& body = sim.bodies()[b];
  std::vector<Eigen::Vector3d> positions;
  for (int node : nodes) positions.push_back(body.positions().segment<3>(3 * node));
  truth.markers.push_back(positions);
  const core::CommandProcessor& commands = session.commands();
  core::Wrench w = commands.fixedReaction(b, Eigen::Vector3d::Zero());
  if (!lab.sensor_grasp.empty()) {
    const bool held = commands.grasps().count(lab.sensor_grasp) > 0;
    w = core::seenFrom(held ? commands.graspReaction(lab.sensor_grasp) : core::Wrench{},
                       Eigen::Isometry3d::Identity());
  }
  if (!lab.sensor_link.empty()) {
    std::vector<core::ContactPair> pairs;
    core::touchingPairs(sim, pairs);
    const core::ContactLoad load = core::loadOnObstacle(pairs, lab.sensor_link);
    w = core::Wrench{load.force, load.torque, Eigen::Vector3d::Zero()};
  }
  Eigen::Matrix<double, 6, 1> value;
  value << w.force, w.torque;
  truth.wrench.push_back(value);
}

// Runs the session, writing ~applied to the bag; returns the truth at every step.
Truth run(const LabRecording& lab, rosbag::Bag& bag) {
  const core::SceneSpec spec = io::parseScene(lab.scene_yaml, "lab.yaml", ".");
  std::vector<std::string> warnings;
  // The lab's node was set up for the loads it applied.
  const double unlimited = std::numeric_limits<double>::infinity();
  core::Session session(spec, io::readMeshes(spec, &warnings),
                        core::CommandLimits{unlimited, unlimited, unlimited});
  core::MeshCatalogue catalogue;
  session.setListener([&](const core::AppliedCommand& applied) {
    deformable_sim::Applied message = ros_layer::toMessage(applied.command, catalogue);
    message.header.stamp = kStart + ros::Duration(applied.step * spec.dt);
    message.header.frame_id = kWorld;
    message.episode = applied.episode;
    message.step = applied.step;
    bag.write("/deformable_sim/applied", message.header.stamp, message);
  });
  const core::Simulation& sim = session.simulation();
  const core::Body& body = sim.bodies()[sim.bodyIndex(lab.body)];
  std::vector<int> nodes;
  for (const TrackedNode& marker : lab.markers) nodes.push_back(nodeAt(body, marker.at));
  Truth truth;
  std::vector<core::StepReport> reports;
  const long steps = static_cast<long>(std::ceil(lab.duration / spec.dt)) + 1;
  recordStep(lab, session, nodes, truth);
  for (long k = 0; k < steps; ++k) {
    const auto range = lab.commands.equal_range(k);
    for (auto it = range.first; it != range.second; ++it) session.apply(it->second);
    session.step(reports);
    recordStep(lab, session, nodes, truth);
  }
  return truth;
}

template <typename Value>
Value interpolate(const std::vector<Value>& steps, double dt, double t) {
  const double k = t / dt;
  const std::size_t before = static_cast<std::size_t>(k);
  const double f = k - static_cast<double>(before);
  return (1.0 - f) * steps[before] + f * steps[before + 1];
}

void writeMarkers(const LabRecording& lab, const Truth& truth, double dt, rosbag::Bag& bag,
                  std::mt19937& random) {
  std::normal_distribution<double> noise(0.0, lab.marker_noise);
  const long outlier_every = lab.marker_outliers > 0.0 ? std::lround(1.0 / lab.marker_outliers) : 0;
  long sample = 0;
  for (double t = 0.0; t <= lab.duration; t += 1.0 / lab.marker_rate, ++sample) {
    const double glitch = outlier_every > 0 && sample % outlier_every == 0 ? 0.05 : 0.0;
    tf2_msgs::TFMessage message;
    const ros::Time stamp = kStart + ros::Duration(t);
    for (std::size_t m = 0; m < lab.markers.size(); ++m) {
      std::vector<Eigen::Vector3d> column;
      for (const auto& step : truth.markers) column.push_back(step[m]);
      const Eigen::Vector3d p = interpolate(column, dt, t);
      geometry_msgs::TransformStamped transform;
      transform.header.stamp = stamp;
      transform.header.frame_id = kWorld;
      transform.child_frame_id = lab.markers[m].frame;
      transform.transform.translation.x = p.x() + noise(random);
      transform.transform.translation.y = p.y() + noise(random);
      transform.transform.translation.z = p.z() + noise(random) + glitch;
      transform.transform.rotation.w = 1.0;
      message.transforms.push_back(transform);
    }
    bag.write("/tf", stamp, message);
  }
}

// Where a turning sensor's frame is at time t (still: lab.sensor_pose).
Eigen::Isometry3d sensorPose(const LabRecording& lab, double t) {
  return Eigen::Translation3d(lab.sensor_pose.translation()) *
         Eigen::AngleAxisd(lab.sensor_turn_rate * t, Eigen::Vector3d::UnitZ()) *
         Eigen::Isometry3d(lab.sensor_pose.linear());
}

// The sensor's frame at time t on `topic`: /tf_static once for a still one, as a robot's
// description would put it there; /tf at every sample for a turning one.
void writeSensorFrame(const LabRecording& lab, double t, const ros::Time& stamp,
                      const std::string& topic, rosbag::Bag& bag) {
  geometry_msgs::TransformStamped transform = tf2::eigenToTransform(sensorPose(lab, t));
  transform.header.stamp = stamp;
  transform.header.frame_id = kWorld;
  transform.child_frame_id = lab.sensor_frame;
  tf2_msgs::TFMessage message;
  message.transforms.push_back(transform);
  bag.write(topic, stamp, message);
}

void writeSensor(const LabRecording& lab, const Truth& truth, double dt, rosbag::Bag& bag,
                 std::mt19937& random) {
  const bool turns = lab.sensor_turn_rate != 0.0;
  if (lab.sensor_frame != kWorld && !turns) writeSensorFrame(lab, 0.0, kStart, "/tf_static", bag);
  std::normal_distribution<double> force(0.0, lab.force_noise), torque(0.0, lab.torque_noise);
  for (double t = 0.0; t <= lab.duration; t += 1.0 / lab.sensor_rate) {
    const Eigen::Matrix<double, 6, 1> w = interpolate(truth.wrench, dt, t);
    const core::Wrench seen =
        core::seenFrom(core::Wrench{w.head<3>(), w.tail<3>(), Eigen::Vector3d::Zero()},
                       turns ? sensorPose(lab, t) : lab.sensor_pose);
    geometry_msgs::WrenchStamped message;
    message.header.stamp = kStart + ros::Duration(t + lab.sensor_clock_offset);
    if (turns) writeSensorFrame(lab, t, message.header.stamp, "/tf", bag);
    message.header.frame_id = lab.sensor_frame;
    message.wrench.force.x = seen.force.x() + force(random);
    message.wrench.force.y = seen.force.y() + force(random);
    message.wrench.force.z = seen.force.z() + force(random);
    message.wrench.torque.x = seen.torque.x() + torque(random);
    message.wrench.torque.y = seen.torque.y() + torque(random);
    message.wrench.torque.z = seen.torque.z() + torque(random);
    bag.write(lab.sensor_topic, message.header.stamp, message);
  }
}

}  // namespace

// ~scene as the node latches it: its scene file's text and every body's mesh.
void writeNodeScene(const LabRecording& lab, rosbag::Bag& bag) {
  const core::SceneSpec spec = io::parseScene(lab.node_scene_yaml, "lab.yaml", ".");
  std::vector<std::string> warnings, names;
  for (const core::BodySpec& body : spec.bodies) names.push_back(body.name);
  core::MeshCatalogue catalogue;
  deformable_sim::Scene message = ros_layer::toSceneMessage(
      "lab.yaml", lab.node_scene_yaml, spec.dt, 1, io::readMeshes(spec, &warnings), {}, names,
      spec.obstacles, {}, catalogue);
  message.header.stamp = kStart;
  message.world_frame = kWorld;
  bag.write("/deformable_sim/scene", kStart, message);
}

void recordLab(const LabRecording& lab, const std::string& path) {
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  if (!lab.node_scene_yaml.empty()) writeNodeScene(lab, bag);
  const Truth truth = run(lab, bag);
  const double dt = io::parseScene(lab.scene_yaml, "lab.yaml", ".").dt;
  std::mt19937 random(lab.seed);
  if (!lab.markers.empty()) writeMarkers(lab, truth, dt, bag, random);
  if (!lab.sensor_topic.empty()) writeSensor(lab, truth, dt, bag, random);
  bag.close();
}

}  // namespace deformable_sim::test
