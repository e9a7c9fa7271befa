// A body from a surface mesh file (STL, DAE, OBJ): read it, then voxelize and embed it
// (core/surface_body.h).
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "deformable_sim/core/surface_body.h"

namespace deformable_sim::io {

/// Reads the surface at `path` (a file path; resolve URIs with resolveMeshUri first) and makes a
/// body of it. Throws TriangleMeshError naming the file when it is missing, empty, of an unknown
/// format, encloses nothing or the settings make no grid; a warning naming the file and its
/// separate pieces is appended to `warnings`. The surface is placed at `pose` first.
core::SurfaceBody readSurfaceBody(const std::string& path, const core::VoxelSettings& settings,
                                  std::vector<std::string>* warnings,
                                  const Eigen::Isometry3d& pose = Eigen::Isometry3d::Identity());

}  // namespace deformable_sim::io
