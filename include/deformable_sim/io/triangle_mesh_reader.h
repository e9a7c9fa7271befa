// Surface meshes (STL ascii and binary, COLLADA .dae, Wavefront .obj and the other formats assimp
// reads) for mesh obstacles and URDF collision meshes, and the URIs that name them.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <stdexcept>
#include <string>

#include "deformable_sim/core/triangle_mesh.h"

namespace deformable_sim::io {

class TriangleMeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Turns a `package://pkg/path` URI into a file path. The ROS layer provides one (it knows where
/// packages are); the ROS-free tools have none.
using PackageResolver = std::function<std::string(const std::string& uri)>;

/// The file path that `uri` names: `file:///abs/path` and plain paths as they are, `package://`
/// through `resolver`. Throws TriangleMeshError for a `package://` URI without a resolver (or one
/// that finds nothing) and for other schemes.
std::string resolveMeshUri(const std::string& uri, const PackageResolver& resolver = {});

/// Reads the triangles of every mesh in the file, with the file's own transforms and units
/// applied and then multiplied by `scale` per axis. Positions that coincide exactly (an STL
/// repeats each vertex for every triangle) become one vertex; triangles left with fewer than
/// three distinct vertices are dropped. Throws TriangleMeshError naming the file when it is
/// missing, of an unknown format, unreadable, or holds no triangle.
core::TriangleMesh readTriangleMesh(const std::string& path,
                                    const Eigen::Vector3d& scale = Eigen::Vector3d::Ones());

}  // namespace deformable_sim::io
