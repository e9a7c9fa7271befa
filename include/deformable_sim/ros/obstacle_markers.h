// The scene's obstacles as rviz markers, for the node's latched ~obstacles: what the bodies cannot
// go through, drawn where the simulation has it.
#pragma once

#include <std_msgs/Header.h>
#include <visualization_msgs/MarkerArray.h>

#include <vector>

#include "deformable_sim/core/geometry/shape.h"

namespace deformable_sim::ros_layer {

/// A DELETEALL (so that obstacles that are gone disappear), then one marker a shape, id = its
/// index, in a neutral grey: a CUBE, SPHERE or CYLINDER posed and sized as the shape, a mesh as a
/// MESH_RESOURCE of its file (scaled as it was read), or as a TRIANGLE_LIST of its triangles when
/// it has no file. In the namespace "links" for a shape of one of `links` (a robot's, which a
/// RobotModel display draws already: an rviz config hides that namespace), else "obstacles".
visualization_msgs::MarkerArray obstacleMarkers(const std::vector<core::PlacedShape>& obstacles,
                                                const std_msgs::Header& header,
                                                const std::vector<std::string>& links = {});

}  // namespace deformable_sim::ros_layer
