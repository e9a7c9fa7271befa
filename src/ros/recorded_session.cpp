#include "deformable_sim/ros/recorded_session.h"

#include <rosbag/bag.h>
#include <rosbag/exceptions.h>
#include <rosbag/view.h>

#include <set>

#include "deformable_sim/Applied.h"
#include "deformable_sim/BodyState.h"
#include "deformable_sim/ros/obstacle_mesh_messages.h"
#include "deformable_sim/ros/replay.h"
#include "deformable_sim/ros/session_messages.h"

namespace deformable_sim::ros_layer {

namespace {

// The nodes whose ~scene (or ~applied) the bag holds: /a/b for a topic /a/b/scene.
std::set<std::string> recordedNodes(const rosbag::Bag& bag, const std::string& type = "Scene",
                                    const std::string& suffix = "/scene") {
  std::set<std::string> nodes;
  rosbag::View scenes(bag, rosbag::TypeQuery("deformable_sim/" + type));
  for (const rosbag::ConnectionInfo* connection : scenes.getConnections()) {
    nodes.insert(connection->topic.substr(0, connection->topic.size() - suffix.size()));
  }
  return nodes;
}

std::string chooseNode(const rosbag::Bag& bag, const std::string& path,
                       const std::string& requested, bool scene_required) {
  std::set<std::string> nodes = recordedNodes(bag);
  if (nodes.empty() && !scene_required) nodes = recordedNodes(bag, "Applied", "/applied");
  if (nodes.empty() && !scene_required) {
    throw ReplayError(path +
                      ": no ~applied (deformable_sim/Applied) message: record the node's "
                      "~applied topic with the session");
  }
  if (nodes.empty()) {
    throw ReplayError(path +
                      ": no deformable_sim/Scene message: record the node's ~scene topic "
                      "(latched) with the session, e.g. rosbag record -a");
  }
  if (requested.empty() && nodes.size() > 1) {
    std::string list;
    for (const std::string& n : nodes) list += (list.empty() ? "" : ", ") + n;
    throw ReplayError(path + ": sessions of several nodes (" + list + "): choose one with --node");
  }
  const std::string node = requested.empty() ? *nodes.begin() : requested;
  if (nodes.count(node) == 0) throw ReplayError(path + ": no scene of node '" + node + "'");
  return node;
}

template <typename Message>
typename Message::ConstPtr instantiate(const rosbag::MessageInstance& m, const std::string& path) {
  typename Message::ConstPtr message = m.instantiate<Message>();
  if (!message) throw ReplayError(path + ": " + m.getTopic() + " is of another message version");
  return message;
}

// Points or vectors as the 3n entries of one vector.
template <typename Entry>
Eigen::VectorXd stacked(const std::vector<Entry>& entries) {
  Eigen::VectorXd x(3 * static_cast<Eigen::Index>(entries.size()));
  for (std::size_t i = 0; i < entries.size(); ++i)
    x.segment<3>(3 * i) << entries[i].x, entries[i].y, entries[i].z;
  return x;
}

void addState(const BodyState& message, RecordedSession& session) {
  const core::RecordedStateKey key{static_cast<long>(message.episode),
                                   static_cast<long>(message.step), message.body};
  if (session.recording.states.count(key) > 0) return;  // a paused node repeats its last state
  session.recording.states.emplace(
      key, core::RecordedState{stacked(message.positions), stacked(message.velocities),
                               session.state_headers.size()});
  session.state_headers.push_back(message.header);
}

void addCommand(const Applied& message, core::MeshCatalogue& meshes, RecordedSession& session) {
  try {
    session.recording.log.push_back(core::AppliedCommand{static_cast<long>(message.episode),
                                                         static_cast<long>(message.step),
                                                         fromMessage(message, meshes)});
  } catch (const core::CommandError&) {
    ++session.unknown_commands;
  }
}

void readMessages(const rosbag::Bag& bag, const std::string& path, RecordedSession& session) {
  const std::string& node = session.node;
  rosbag::View view(bag, rosbag::TopicQuery({node + "/scene", node + "/applied", node + "/state"}));
  bool have_scene = false;
  // Read once the scene is known: a command may name a mesh obstacle that ~scene carries.
  std::vector<Applied::ConstPtr> applied;
  for (const rosbag::MessageInstance& m : view) {
    if (m.getTopic() == node + "/scene") {
      const Scene::ConstPtr scene = instantiate<Scene>(m, path);
      if (!have_scene) session.scene = *scene;
      have_scene = true;
    } else if (m.getTopic() == node + "/applied") {
      applied.push_back(instantiate<Applied>(m, path));
      const Applied& a = *applied.back();
      session.applied_stamps.push_back(
          {a.header, static_cast<long>(a.episode), static_cast<long>(a.step)});
    } else {
      addState(*instantiate<BodyState>(m, path), session);
    }
  }
  core::MeshCatalogue meshes;
  try {
    receive(session.scene.obstacle_meshes, meshes);
  } catch (const core::CommandError& e) {
    throw ReplayError(path + ": the recorded scene: " + e.what());
  }
  for (const Applied::ConstPtr& message : applied) addCommand(*message, meshes, session);
}

}  // namespace

RecordedSession readRecordedSession(const std::string& path, const std::string& node,
                                    bool scene_required) {
  RecordedSession session;
  try {
    rosbag::Bag bag(path, rosbag::bagmode::Read);
    session.node = chooseNode(bag, path, node, scene_required);
    readMessages(bag, path, session);
  } catch (const rosbag::BagUnindexedException&) {
    throw ReplayError(path +
                      ": the bag has no index: it was truncated or its recording did not end "
                      "cleanly (rosbag reindex may repair it)");
  } catch (const rosbag::BagException& e) {
    throw ReplayError(path + ": cannot read the bag: " + e.what());
  }
  return session;
}

}  // namespace deformable_sim::ros_layer
