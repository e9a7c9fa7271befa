#include "deformable_sim/ros/contact_outputs.h"

#include "deformable_sim/Contacts.h"
#include "deformable_sim/ros/conversions.h"

namespace deformable_sim::ros_layer {

namespace {

ContactPair toMessage(const core::ContactPair& pair, const core::Simulation& sim) {
  ContactPair m;
  m.body = sim.bodies()[pair.body].name();
  m.kind = pair.kind == core::ContactPair::Kind::kObstacle ? ContactPair::OBSTACLE
           : pair.kind == core::ContactPair::Kind::kBody   ? ContactPair::BODY
                                                           : ContactPair::SELF;
  m.other = pair.other;
  m.force = toVector3(pair.load.force);
  m.torque = toVector3(pair.load.torque - pair.load.centre.cross(pair.load.force));
  m.centre = toPoint(pair.load.centre);
  m.points = static_cast<uint32_t>(pair.load.points);
  m.depth = pair.load.depth;
  m.penetration = pair.load.penetration;
  return m;
}

}  // namespace

ContactOutputs::ContactOutputs(ros::NodeHandle& private_node, const std::vector<std::string>& links,
                               std::string world_frame)
    : world_frame_(std::move(world_frame)) {
  contacts_pub_ = private_node.advertise<Contacts>("contacts", 10);
  for (const std::string& link : links) {
    try {
      link_pubs_.emplace_back(link, private_node.advertise<geometry_msgs::WrenchStamped>(
                                        "contacts/" + link + "/wrench", 10));
    } catch (const ros::InvalidNameException& e) {
      ROS_WARN("link '%s' gets no contact wrench topic: %s", link.c_str(), e.what());
    }
  }
}

void ContactOutputs::publish(const core::Session& session,
                             const core::LinkedObstacles::FramePose& link_pose,
                             const ros::Time& stamp) {
  const core::Simulation& sim = session.simulation();
  core::touchingPairs(sim, pairs_);
  if (contacts_pub_.getNumSubscribers() > 0) {
    Contacts message;
    message.header.stamp = stamp;
    message.header.frame_id = world_frame_;
    message.step = static_cast<uint64_t>(sim.stepCount());
    for (const core::ContactPair& pair : pairs_) message.pairs.push_back(toMessage(pair, sim));
    contacts_pub_.publish(message);
  }
  for (const auto& [link, publisher] : link_pubs_) {
    if (publisher.getNumSubscribers() == 0) continue;
    const std::optional<Eigen::Isometry3d> pose = link_pose(link);
    if (!pose) continue;
    const core::ContactLoad load = core::loadOnObstacle(pairs_, link);
    const core::Wrench wrench{load.force, load.torque, Eigen::Vector3d::Zero()};
    publisher.publish(toMessage(wrench, link, *pose, stamp));
  }
}

}  // namespace deformable_sim::ros_layer
