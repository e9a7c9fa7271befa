#include "deformable_sim/ros/fit_checks.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <type_traits>
#include <variant>

#include "deformable_sim/identify/fit_spec.h"

namespace deformable_sim::ros_layer {

using identify::FitSpecError;

namespace {

/// The body a command names (empty: none, or the scene's only body).
std::string commandBody(const core::SessionCommand& command) {
  return std::visit(
      [](const auto& c) -> std::string {
        if constexpr (std::is_same_v<std::decay_t<decltype(c)>, core::WrenchCommand> ||
                      std::is_same_v<std::decay_t<decltype(c)>, core::FixCommand> ||
                      std::is_same_v<std::decay_t<decltype(c)>, core::GraspCommand> ||
                      std::is_same_v<std::decay_t<decltype(c)>, core::TuneCommand>) {
          return c.body;
        } else {
          return "";
        }
      },
      command);
}

}  // namespace

void checkSceneIsTheBags(const RecordedSession& session, const core::SceneSpec& spec,
                         const std::vector<core::Mesh>& meshes) {
  std::string names;
  for (const core::BodySpec& body : spec.bodies) names += (names.empty() ? "" : ", ") + body.name;
  for (const core::AppliedCommand& applied : session.recording.log) {
    const std::string body = commandBody(applied.command);
    const bool known = std::any_of(spec.bodies.begin(), spec.bodies.end(),
                                   [&](const core::BodySpec& b) { return b.name == body; });
    if (!body.empty() && !known) {
      throw FitSpecError(
          "scene: the bag's log commands body '" + body + "' (episode " +
          std::to_string(applied.episode) + ", step " + std::to_string(applied.step) +
          "), which the scene does not have (it has " + names + "): the scene is not the bag's");
    }
  }
  if (session.scene.meshes.empty()) return;  // no ~scene in the bag: nothing more to compare
  if (std::abs(session.scene.dt - spec.dt) > 1e-12 * spec.dt) {
    throw FitSpecError("scene: its dt is " + std::to_string(spec.dt) +
                       " s, the bag's node stepped " + std::to_string(session.scene.dt) +
                       " s: the scene is not the bag's");
  }
  for (const MeshData& recorded : session.scene.meshes) {
    for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
      if (spec.bodies[b].name != recorded.body) continue;
      if (static_cast<long>(recorded.node_ids.size()) != meshes[b].numNodes()) {
        throw FitSpecError("scene: body '" + recorded.body + "' has " +
                           std::to_string(meshes[b].numNodes()) + " nodes, the bag's " +
                           std::to_string(recorded.node_ids.size()) +
                           ": the scene is not the bag's");
      }
    }
  }
}

void checkSourcesAppear(const identify::FitSpec& fit, const core::Recording& recording,
                        const core::SceneSpec& spec) {
  std::set<std::string> grasps, links;
  for (const core::PlacedShape& obstacle : spec.obstacles) links.insert(obstacle.name);
  for (const core::AppliedCommand& applied : recording.log) {
    if (const auto* grasp = std::get_if<core::GraspCommand>(&applied.command)) {
      grasps.insert(grasp->name);
    } else if (const auto* set = std::get_if<core::SetObstaclesCommand>(&applied.command)) {
      for (const core::PlacedShape& obstacle : set->obstacles) links.insert(obstacle.name);
    }
  }
  const auto list = [](const std::set<std::string>& names) {
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
    return text.empty() ? std::string("none") : text;
  };
  for (const identify::ObservationSpec& o : fit.observations) {
    if (o.source == identify::ObservationSpec::Source::kGrasp && !grasps.count(o.name)) {
      throw FitSpecError(o.key + ".grasp: the bag's log has no grasp '" + o.name +
                         "' (its grasps: " + list(grasps) + ")");
    }
    if (o.source == identify::ObservationSpec::Source::kLink && !links.count(o.name)) {
      throw FitSpecError(o.key + ".link: neither the scene nor the bag's log has an obstacle '" +
                         o.name + "' (they have: " + list(links) + ")");
    }
  }
}

}  // namespace deformable_sim::ros_layer
