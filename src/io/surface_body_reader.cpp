#include "deformable_sim/io/surface_body_reader.h"

#include <stdexcept>

#include "deformable_sim/io/triangle_mesh_reader.h"

namespace deformable_sim::io {

core::SurfaceBody readSurfaceBody(const std::string& path, const core::VoxelSettings& settings,
                                  std::vector<std::string>* warnings,
                                  const Eigen::Isometry3d& pose) {
  int collapsed = 0;
  core::TriangleMesh surface = readTriangleMesh(path, Eigen::Vector3d::Ones(), &collapsed);
  for (Eigen::Vector3d& v : surface.vertices) v = pose * v;
  std::vector<std::string> found;
  try {
    core::SurfaceBody body = core::bodyFromSurface(std::move(surface), settings, &found, collapsed);
    if (warnings) {
      for (const std::string& w : found) warnings->push_back("surface '" + path + "': " + w);
    }
    return body;
  } catch (const std::invalid_argument& e) {
    throw TriangleMeshError("surface '" + path + "': " + e.what());
  }
}

}  // namespace deformable_sim::io
