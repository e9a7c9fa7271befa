// Collision geometry of a robot description (URDF, read with urdfdom): the boxes, spheres,
// cylinders and meshes (STL, DAE, OBJ) of each link, posed in the link's frame. They become
// obstacles and grasp regions.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "deformable_sim/core/geometry/shape.h"
#include "deformable_sim/io/triangle_mesh_reader.h"

namespace deformable_sim::io {

class UrdfError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Every link of the URDF text with its collision shapes (possibly none), each named after its
/// link. A <mesh filename=... scale=...> is read through readTriangleMesh: `package://` URIs
/// through `resolver`, relative paths against `base_directory` (when not empty). A mesh that
/// cannot be read is skipped with a warning naming the link, the file and why. Throws UrdfError
/// when the text is not a valid URDF.
std::map<std::string, std::vector<core::PlacedShape>> readCollisionShapes(
    const std::string& urdf_xml, std::vector<std::string>* warnings,
    const PackageResolver& resolver = {}, const std::string& base_directory = "");

/// The shapes of `link`; throws UrdfError naming the link (and the links there are) when it is
/// not in `shapes` or has no collision shape.
const std::vector<core::PlacedShape>& linkShapes(
    const std::map<std::string, std::vector<core::PlacedShape>>& shapes, const std::string& link);

}  // namespace deformable_sim::io
