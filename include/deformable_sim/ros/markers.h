// rviz markers of a body: its surface as a triangle list, and what acts on it.
#pragma once

#include <std_msgs/Header.h>
#include <visualization_msgs/Marker.h>
#include <visualization_msgs/MarkerArray.h>

#include <string>
#include <vector>

#include "deformable_sim/core/body.h"
#include "deformable_sim/core/commands.h"
#include "deformable_sim/core/mesh.h"

namespace deformable_sim::ros_layer {

/// Fills `marker` (reused between calls) with the body's current surface: TRIANGLE_LIST, three
/// points per triangle in the mesh's outward order, namespace = body name. With `strain` (one per
/// node, dimensionless) the vertices are coloured from blue (0) to red (>= strain_scale).
void fillSurfaceMarker(const core::Body& body, const std::vector<core::Triangle>& surface,
                       const std::vector<double>* strain, double strain_scale,
                       visualization_msgs::Marker& marker);

/// Markers of what acts on the bodies: fixed nodes (red spheres), grasped nodes (yellow spheres),
/// node groups (blue points) and applied wrenches (green arrows from the application point, 0.1 m
/// per N). Starts with a DELETEALL so that markers of things that are gone disappear.
visualization_msgs::MarkerArray interactionMarkers(const std::vector<core::Body>& bodies,
                                                   const core::CommandProcessor& commands,
                                                   const std_msgs::Header& header);

}  // namespace deformable_sim::ros_layer
