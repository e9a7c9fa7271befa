// Collision geometry of a robot description (URDF, read with urdfdom): the boxes, spheres and
// cylinders of each link, posed in the link's frame. They become obstacles and grasp regions.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "deformable_sim/core/shape.h"

namespace deformable_sim::io {

class UrdfError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Every link of the URDF text with its primitive collision shapes (possibly none), each named
/// after its link. Mesh collision geometry is skipped with a warning naming the link. Throws
/// UrdfError when the text is not a valid URDF.
std::map<std::string, std::vector<core::PlacedShape>> readCollisionShapes(
    const std::string& urdf_xml, std::vector<std::string>* warnings);

/// The shapes of `link`; throws UrdfError naming the link (and the links there are) when it is
/// not in `shapes` or has no box, sphere or cylinder.
const std::vector<core::PlacedShape>& linkShapes(
    const std::map<std::string, std::vector<core::PlacedShape>>& shapes, const std::string& link);

}  // namespace deformable_sim::io
