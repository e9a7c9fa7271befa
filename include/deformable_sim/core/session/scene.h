// What a scene asks for, as plain data: time step, effects, solver, and the bodies with their
// meshes, materials, fixed nodes and loads. Filled by the scene-file reader (io/scene_file.h) or
// in code; turned into a running Simulation by core/session/simulation.h.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "deformable_sim/core/bodies/body.h"
#include "deformable_sim/core/contact/contact.h"
#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/material.h"
#include "deformable_sim/core/elements/selection.h"
#include "deformable_sim/core/geometry/shape.h"
#include "deformable_sim/core/solvers/linear_solver.h"
#include "deformable_sim/core/surface_bodies/voxelization.h"

namespace deformable_sim::core {

struct LoadSpec {
  enum class Kind {
    kTraction,    ///< value in Pa on the boundary faces whose nodes are all selected
    kTotalForce,  ///< value in N split equally among the selected nodes
    kWrench,      ///< force value (N) and torque (N m) about the selection's rest mass centroid,
                  ///< spread by mass (core/bodies/wrench.h)
  };
  NodeSelection where;
  Kind kind = Kind::kTraction;
  Eigen::Vector3d value = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  ///< kWrench only
};

/// A generated structured mesh (core/elements/box_mesh.h) instead of a mesh file.
struct BoxMeshSpec {
  Eigen::Vector3d min = Eigen::Vector3d::Zero();  ///< m
  Eigen::Vector3d max = Eigen::Vector3d::Ones();  ///< m
  Eigen::Vector3i cells = Eigen::Vector3i::Ones();
  BoxElement element = BoxElement::kTetrahedron;  ///< what each cube is cut into
};

/// A body made from a surface (core/surface_bodies/surface_body.h) instead of a volume mesh.
struct SurfaceMeshSpec {
  std::string file;       ///< path or package:// URI of the surface (STL, DAE, OBJ); or empty
  std::string urdf_link;  ///< or the link of the robot description whose visual mesh it is
  VoxelSettings voxels;   ///< the grid's cell size or cells along the longest side
  /// Where the surface is placed in the scene (keys position, rpy) before it is voxelized on a
  /// grid along the scene's axes.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};

struct BodySpec {
  std::string name;
  BodyModel model = BodyModel::kFiniteElement;
  /// The body's own effects instead of the scene's (key `effects` of the body).
  std::optional<BodyEffects> effects;
  std::string mesh;                             ///< path of the mesh file, or empty with box_mesh
  std::optional<BoxMeshSpec> box_mesh;          ///< generated mesh, when there is no mesh file
  std::optional<SurfaceMeshSpec> surface_mesh;  ///< or a grid made from a surface
  LinearElasticMaterial material;
  std::vector<NodeSelection> fixed;
  std::vector<LoadSpec> loads;
  std::map<std::string, NodeSelection> groups;  ///< named node groups (by rest position)
  /// A wrench given in a frame that is not one of the body's groups acts on the body's nodes
  /// within this distance of the frame's origin, m.
  double wrench_radius = 0.05;
  /// The velocity every node starts with, m/s (key `velocity`): a body thrown or dropped at
  /// speed. A body with fixed nodes starts at rest.
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  /// The colour it is drawn in, red, green and blue in [0, 1] (key `colour`); unset: the
  /// palette's colour of its index (core/outputs/body_colours.h).
  std::optional<Eigen::Vector3d> colour;
};

/// Where a scene file gives the entries that can only be checked once the spec is built (a mesh
/// file, a selection that must select nodes), so that those errors can name the file and line.
struct SceneSource {
  std::string file;  ///< as the reader was given it; empty for a scene made in code
  /// 1-based line of each such key ("bodies[0]", "bodies[0].mesh", "bodies[0].groups.tip",
  /// "bodies[0].fixed[1]", "bodies[0].loads[0]").
  std::map<std::string, int> lines;
};

struct SceneSpec {
  double dt = 0.01;  ///< s
  BodyEffects effects;
  std::optional<ContactSettings> contact;  ///< the contact effect: bodies stay out of obstacles
  std::vector<PlacedShape> obstacles;      ///< static obstacles (key `obstacles`)
  /// Links of the robot description whose collision shapes become obstacles posed by tf (the ROS
  /// layer resolves them), and the URDF file to read instead of the robot_description parameter.
  std::vector<std::string> urdf_links;
  std::string urdf_file;
  SolverSettings solver;
  StaticSettings statics;
  std::vector<BodySpec> bodies;
  SceneSource source;
};

}  // namespace deformable_sim::core
