// A body from a surface mesh file (STL, DAE, OBJ): read it, then voxelize and embed it
// (core/surface_bodies/surface_body.h).
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "deformable_sim/core/surface_bodies/surface_body.h"

namespace deformable_sim::io {

/// Reads the surface at `path` (a file path; resolve URIs with resolveMeshUri first) and makes a
/// body of it. Throws TriangleMeshError naming the file when it is missing, empty, of an unknown
/// format, has a non-finite coordinate, encloses nothing or the settings make no grid. The
/// surface check's warnings (core/surface_bodies/surface_check.h: dropped triangles, open edges,
/// turned triangles or shells, voids, crossings) and the separate pieces are appended to
/// `warnings`, each naming the file. The surface is placed at `pose` first.
core::SurfaceBody readSurfaceBody(const std::string& path, const core::VoxelSettings& settings,
                                  std::vector<std::string>* warnings,
                                  const Eigen::Isometry3d& pose = Eigen::Isometry3d::Identity());

}  // namespace deformable_sim::io
