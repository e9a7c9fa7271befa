// Scene files (YAML): read into core::SceneSpec, then into a runnable core::Simulation.
//
//   dt: 0.01                                   # s
//   effects: {gravity: [0, 0, -9.81], warping: true, damping: {mass: 0.0, stiffness: 0.0}}
//   solver: {method: cg, tolerance: 1.0e-6, max_iterations: 1000}    # method: cg | direct
//   static: {load_steps: 1, max_iterations: 200, tolerance: 1.0e-8}
//   bodies:
//     - name: beam
//       mesh: meshes/beam.msh      # relative to the scene file; or {box: {min, max, cells}},
//                                  # or {surface: part.stl, cell_size: 0.01} (or cells: N)
//       model: fem
//       material: {youngs_modulus: 1.0e6, poisson_ratio: 0.3, density: 1000.0}
//       fixed: [{box: {min: [...], max: [...]}}, {nodes: [12, 40]}, {sphere: {center, radius}}]
//       loads: [{box: {...}, traction: [0, 0, -2.5]}, {nodes: [7], total_force: [0, 0, -0.01]}]
//   obstacles:                                 # needs effects: {contact: {friction: 0.5}}
//     - {name: table, box: {size: [1, 1, 0.1]}, position: [0, 0, -0.05], rpy: [0, 0, 0]}
//     - {name: ramp, mesh: {file: ramp.stl, scale: [1, 1, 1]}, position: [..], rpy: [..]}
//                                              # STL, DAE or OBJ, relative to the scene file
//
// Effects that are not named are off. Unknown keys, wrong types and impossible values throw
// SceneError with the file, the line and the key ("scene.yaml:7: bodies[0].material.density: ...").
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "deformable_sim/core/base/spec_error.h"
#include "deformable_sim/core/session/scene.h"
#include "deformable_sim/core/session/simulation.h"
#include "deformable_sim/io/triangle_mesh_reader.h"

namespace deformable_sim::io {

class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Reads the mesh of the obstacle at `key` ("obstacles[2]") from `path` (resolved against the
/// scene file's directory) at `scale`; throws TriangleMeshError. A replay takes the recorded
/// triangles instead of the file.
using ObstacleMeshLoader = std::function<std::shared_ptr<const core::TriangleMeshShape>(
    const std::string& key, const std::string& path, const Eigen::Vector3d& scale)>;

/// "obstacles[k]": the key of the scene's k-th obstacle, in messages and as a mesh's id.
std::string sceneObstacleKey(int index);

/// Parses scene YAML text. `source` names it in messages; relative mesh paths are resolved
/// against `base_directory`. Mesh obstacles are read with `load_mesh`, by default from their
/// files.
core::SceneSpec parseScene(const std::string& yaml_text, const std::string& source,
                           const std::string& base_directory,
                           const ObstacleMeshLoader& load_mesh = {});

/// Reads and parses a scene file.
core::SceneSpec readSceneFile(const std::string& path);
/// The text of the scene file at `path`; throws SceneError when it cannot be opened.
std::string readSceneText(const std::string& path);
/// The scene of `yaml_text` as read from the file `path` (relative paths against its directory);
/// the built-in default scene when both are empty, as the node records a run of it.
core::SceneSpec sceneFromFileText(const std::string& yaml_text, const std::string& path,
                                  const ObstacleMeshLoader& load_mesh = {});

/// Where bodies made from surfaces find what a scene file does not hold: the ROS node can resolve
/// packages and has the robot description; the offline tools have neither.
struct SurfaceSources {
  PackageResolver resolver;       ///< for package:// surfaces and URDF mesh URIs
  std::string robot_description;  ///< URDF text for urdf_link bodies; empty: the scene's urdf file
  /// If set, told how far voxelizing a body's surface is: `done` of the `total` cells of its grid
  /// (core::VoxelProgress), with the body's name.
  std::function<void(const std::string& body, long done, long total)> progress;
};

/// Reads (or generates) every body's mesh, in the order of spec.bodies. Mesh repairs are appended
/// to `warnings`. Throws MeshError for bad or missing mesh files, naming the scene file, line and
/// key first ("scene.yaml:9: bodies[0].mesh: cannot open mesh file 'beam.msh': ...").
/// A body from a surface (`mesh: {surface: ..}` or `{urdf_link: ..}`) gets the grid the surface
/// is voxelized into, and `surfaces` (resized to one per body) the embedded surface to draw it
/// with; `sources` resolve package:// URIs and give the robot description.
std::vector<core::Mesh> readMeshes(
    const core::SceneSpec& spec, std::vector<std::string>* warnings,
    std::vector<std::optional<core::EmbeddedSurface>>* surfaces = nullptr,
    const SurfaceSources& sources = {});

/// Reads every body's mesh and builds the simulation, with the embedded surfaces of bodies made
/// from surfaces (Simulation::embeddedSurface). Mesh repairs are appended to `warnings`.
/// Throws SceneError (bad selections, loads; with the scene file and line of the entry) or
/// MeshError (bad mesh files). `sources` as for readMeshes.
core::Simulation buildSimulation(const core::SceneSpec& spec, std::vector<std::string>* warnings,
                                 const SurfaceSources& sources = {});

/// The message of an error from building `spec` (core::Simulation, core::Session) with the scene
/// file and line of its key in front: "scene.yaml:12: bodies[0].groups.tip: selects no node".
std::string locatedMessage(const core::SceneSpec& spec, const core::SpecError& error);

}  // namespace deformable_sim::io
