#include "deformable_sim/identify/observation_model.h"

namespace deformable_sim::identify {

namespace {

int bodyIndex(const core::Simulation& simulation, const ObservationSpec& spec,
              const std::string& key) {
  const int body = simulation.bodyIndex(spec.body);
  if (body < 0) throw FitSpecError(key + ": the scene has no body '" + spec.body + "'");
  return body;
}

std::string pointText(const Eigen::Vector3d& p) {
  return "[" + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ", " + std::to_string(p.z()) +
         "]";
}

}  // namespace

ObservationModel::ObservationModel(const ObservationSpec& spec, const core::Simulation& simulation,
                                   const Eigen::Isometry3d& sensor_frame)
    : spec_(spec), sensor_frame_(sensor_frame) {
  const bool reactions = spec.kind == ObservationSpec::Kind::kWrench &&
                         spec.source == ObservationSpec::Source::kReactions;
  if (spec.kind == ObservationSpec::Kind::kFrame) {
    body_ = bodyIndex(simulation, spec, spec.key + ".body");
    const auto point = findMaterialPoint(simulation.bodies()[body_].mesh(), spec.at);
    if (!point) {
      throw FitSpecError(spec.key + ".at: " + pointText(spec.at) + " is outside body '" +
                         spec.body + "' at rest");
    }
    point_ = *point;
  } else if (reactions) {
    body_ = bodyIndex(simulation, spec, spec.key + ".reactions");
  }
}

core::Wrench ObservationModel::wrench(const core::Session& session) {
  const core::CommandProcessor& commands = session.commands();
  switch (spec_.source) {
    case ObservationSpec::Source::kReactions:
      return commands.fixedReaction(body_, Eigen::Vector3d::Zero());
    case ObservationSpec::Source::kGrasp:
      if (commands.grasps().count(spec_.name) == 0) return {};
      return commands.graspReaction(spec_.name);
    case ObservationSpec::Source::kLink: {
      core::touchingPairs(session.simulation(), pairs_);
      const core::ContactLoad load = core::loadOnObstacle(pairs_, spec_.name);
      return core::Wrench{load.force, load.torque, Eigen::Vector3d::Zero()};
    }
  }
  return {};
}

Eigen::VectorXd ObservationModel::predict(const core::Session& session) {
  if (spec_.kind == ObservationSpec::Kind::kFrame)
    return point_.position(session.simulation().bodies()[body_].positions());
  const core::Wrench seen = core::seenFrom(wrench(session), sensor_frame_);
  Eigen::VectorXd value(6);
  value << seen.force, seen.torque;
  return value;
}

}  // namespace deformable_sim::identify
