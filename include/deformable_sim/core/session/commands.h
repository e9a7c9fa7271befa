// What a user asks of a running simulation — push on nodes, fix or drag or release them — as plain
// data, and the processor that checks each command and applies it between steps. The ROS layer
// turns messages into these (resolving tf frames to world coordinates); the checks live here so
// they are tested without a roscore.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "deformable_sim/core/elements/selection.h"
#include "deformable_sim/core/geometry/shape.h"
#include "deformable_sim/core/session/command_limits.h"
#include "deformable_sim/core/session/simulation.h"

namespace deformable_sim::core {

/// A refused command; the message names what was wrong. The simulation is unchanged.
class CommandError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Which nodes of a body a command acts on: exactly one of the five. Regions are tested against
/// the current positions, boxes and spheres in the frame `region_pose` (its pose in the world).
struct NodeTarget {
  std::vector<long> node_numbers;  ///< the mesh file's node numbers
  std::string group;               ///< a node group of the body (scene key `groups`)
  std::optional<Box> box;
  std::optional<Sphere> sphere;
  Eigen::Isometry3d region_pose = Eigen::Isometry3d::Identity();
  /// Solids (world poses): the nodes inside any of them or within `shape_margin` (m) of it.
  std::vector<PlacedShape> shapes;
  double shape_margin = 0.0;
  /// All nodes of the body (none of the above given and this set).
  bool whole_body = false;
};

/// A wrench that stays applied until the same source sends another (a zero wrench removes it).
/// Resolved to nodal forces when applied (a dead load): its net force is `force` and its net
/// torque about `point` is `torque`, exactly, on the nodes as they are at that moment.
struct WrenchCommand {
  std::string source;  ///< identity: a frame name, "<body>/<group>", "node_wrench/..."
  std::string body;    ///< empty: the body with a node nearest to the sphere's centre
  NodeTarget nodes;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   ///< N, world frame
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  ///< N m, world frame, about `point`
  std::optional<Eigen::Vector3d> point;              ///< m, world; default: the nodes' centroid
};

/// Fix (hold where they are, or move to targets) or release nodes.
struct FixCommand {
  std::string body;
  NodeTarget nodes;
  bool fix = true;
  /// Fix only: empty (hold where they are), or one target per selected node in the order of
  /// `node_numbers` (regions and groups: ascending node number), m, world.
  std::vector<Eigen::Vector3d> targets;
  /// Fix only: moves every selected node by this from where it is now, m, world.
  std::optional<Eigen::Vector3d> translation;
};

/// Attach the nodes in a region to a frame (a gripper): from then on they follow it rigidly.
struct GraspCommand {
  std::string name;  ///< a grasp of the same name is replaced
  std::string body;  ///< empty: the scene's only body, or the body nearest a sphere region
  NodeTarget nodes;  ///< usually a box or sphere (world); node ids and groups work too
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();  ///< the frame's pose now, world
};

/// A grasp in effect.
struct ActiveGrasp {
  int body = -1;
  std::vector<int> nodes;
  std::vector<Eigen::Vector3d> local;  ///< each node's position in the frame when attached, m
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();  ///< the frame's last pose, world
  std::vector<Eigen::Vector3d> targets;  ///< moveGrasp's buffer for the nodes' world targets
};

/// Force (N) and torque (N m, about `point`) in the world frame.
struct Wrench {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
};

/// The wrench as a sensor at `frame` (its pose in the world) reads it: force and torque in the
/// frame's axes, the torque about the frame's origin.
Wrench seenFrom(const Wrench& wrench, const Eigen::Isometry3d& frame);

/// A wrench in effect, as applied: for markers and the record.
struct ActiveWrench {
  int body = -1;
  std::vector<int> nodes;
  std::vector<Eigen::Vector3d> forces;  ///< N per node
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
};

/// "(x, y, z)", for messages that name a point.
std::string vectorText(const Eigen::Vector3d& v);

class CommandProcessor {
 public:
  /// Keeps a reference to `simulation`; the scene's own loads are kept as the base load.
  explicit CommandProcessor(Simulation& simulation, CommandLimits limits = {});

  /// Each throws CommandError naming the problem and leaves the simulation as it was; on success
  /// returns the number of nodes it acted on (0 for a wrench that cleared its source).
  int apply(const WrenchCommand& command);
  int apply(const FixCommand& command);

  /// Attaches a grasp; refuses (CommandError) empty regions, non-finite poses and nodes that are
  /// already fixed or grasped. Returns the number of nodes attached.
  int apply(const GraspCommand& command);
  /// Returns the grasp's nodes to free motion where they are, with their velocity (no jump).
  /// False if there is no grasp of that name.
  bool releaseGrasp(const std::string& name);
  /// Moves a grasp's frame: its nodes reach `frame * local` at the end of the next step.
  void moveGrasp(const std::string& name, const Eigen::Isometry3d& frame);
  const std::map<std::string, ActiveGrasp>& grasps() const { return grasps_; }
  /// What the grasp exerts on the body in the last step: the sum of its nodes' constraint forces
  /// and their torque about the frame's origin.
  Wrench graspReaction(const std::string& name) const;
  /// The grasped body's best-fit frame seen from the grasp's frame: how it slips or sags in the
  /// hand.
  Eigen::Isometry3d objectInGrasp(const std::string& name) const;
  /// What all constrained nodes of a body that no grasp holds exert on it, torque about `point`.
  Wrench fixedReaction(int body, const Eigen::Vector3d& point) const;

  /// Removes the wrench of `source`; false if there was none.
  bool clearWrench(const std::string& source);
  const std::map<std::string, ActiveWrench>& activeWrenches() const { return wrenches_; }
  const CommandLimits& limits() const { return limits_; }
  void setLimits(const CommandLimits& limits) { limits_ = limits; }

 private:
  int findBody(const std::string& name, const NodeTarget& nodes) const;
  std::vector<int> resolve(const Body& body, const NodeTarget& nodes) const;
  void updateExternalForces(int body);
  /// Adds the nodal forces of the active wrenches on `body` (but the one from `except`).
  void addWrenchForces(int body, const std::string* except, Eigen::VectorXd& forces) const;

  Simulation& simulation_;
  CommandLimits limits_;
  std::vector<Eigen::VectorXd> base_forces_;  ///< per body: the scene's loads
  std::map<std::string, ActiveWrench> wrenches_;
  std::map<std::string, ActiveGrasp> grasps_;
  /// The grasp holding node `node` of body `body`, or nullptr.
  const std::string* graspOf(int body, int node) const;
};

}  // namespace deformable_sim::core
