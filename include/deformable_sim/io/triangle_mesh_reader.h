// Surface meshes (STL ascii and binary, COLLADA .dae, Wavefront .obj and the other formats assimp
// reads) for mesh obstacles and URDF collision meshes, and the URIs that name them.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <stdexcept>
#include <string>

#include "deformable_sim/core/geometry/triangle_mesh.h"

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

/// The URI a viewer loads a mesh by: `uri` itself when it is a `package://` URI, else `file://`
/// followed by `path` (the file it was read from) made absolute.
std::string meshResourceUri(const std::string& uri, const std::string& path);

/// Reads the triangles of every mesh in the file, with the file's own transforms and units
/// applied and then multiplied by `scale` per axis. Positions that coincide exactly (an STL
/// repeats each vertex for every triangle) become one vertex; triangles left with fewer than
/// three distinct vertices are dropped, and counted in `collapsed` if given. Throws
/// TriangleMeshError naming the file when it is missing, of an unknown format, unreadable, holds
/// no triangle, or has a corner with a coordinate that is not finite (NaN or infinite: "corner 2
/// of triangle 5 has a non-finite coordinate (nan 0 1)", triangles counted from 1).
core::TriangleMesh readTriangleMesh(const std::string& path,
                                    const Eigen::Vector3d& scale = Eigen::Vector3d::Ones(),
                                    int* collapsed = nullptr);

/// As readTriangleMesh, from the file's bytes: `format` is the extension that names the format
/// ("stl" for ascii and binary STL alike, "obj", ...) and `name` is what errors call the file. A
/// format that refers to other files (an OBJ's .mtl) reads without them.
core::TriangleMesh readTriangleMeshFromMemory(
    const std::string& bytes, const std::string& format, const std::string& name,
    const Eigen::Vector3d& scale = Eigen::Vector3d::Ones(), int* collapsed = nullptr);

}  // namespace deformable_sim::io
