// rviz markers of a body: its surface as a triangle list, and what acts on it.
#pragma once

#include <std_msgs/Header.h>
#include <visualization_msgs/Marker.h>
#include <visualization_msgs/MarkerArray.h>

#include <string>
#include <vector>

#include "deformable_sim/core/bodies/body_list.h"
#include "deformable_sim/core/outputs/contact_pairs.h"
#include "deformable_sim/core/outputs/drawn_surfaces.h"
#include "deformable_sim/core/session/commands.h"
#include "deformable_sim/core/session/simulation.h"

namespace deformable_sim::ros_layer {

/// The strain a surface vertex is drawn red at, unless the node is told otherwise.
constexpr double kDefaultStrainScale = 0.1;

/// The bodies' surfaces as rviz markers, for the node's ~mesh and the replay's output bag: a
/// TRIANGLE_LIST a body (core::DrawnSurfaces' corners), namespace = the body's name, in the
/// body's colour (`colours`, by body index; core::paletteColour where it has none). A body with
/// stress_colouring has its vertices coloured by their strain instead, from blue (0) to red (>=
/// strain_scale). A marker with a lifetime (s, > 0) vanishes from rviz when it is not sent again
/// within it; 0: it stays until replaced.
class SurfaceMarkers {
 public:
  SurfaceMarkers(const core::Simulation& simulation, double strain_scale,
                 std::vector<Eigen::Vector3d> colours = {}, double lifetime_s = 0.0);
  /// The marker of `body`, the `index`th of the bodies, as it is now (reused between calls).
  const visualization_msgs::Marker& marker(const core::Body& body, int index,
                                           const std_msgs::Header& header);

 private:
  core::DrawnSurfaces surfaces_;
  double strain_scale_;
  std::vector<Eigen::Vector3d> colours_;
  double lifetime_s_;
  visualization_msgs::Marker marker_;
};

/// A marker that tells rviz to forget every marker of its topic.
visualization_msgs::Marker deleteAllMarker(const std_msgs::Header& header = {});

/// Markers of what acts on the bodies: fixed nodes (red spheres), grasped nodes (yellow spheres),
/// node groups (blue points) and applied wrenches (green arrows from the application point, 0.1 m
/// per N). Starts with a DELETEALL so that markers of things that are gone disappear.
visualization_msgs::MarkerArray interactionMarkers(const core::BodyList& bodies,
                                                   const core::CommandProcessor& commands,
                                                   const std_msgs::Header& header);

/// For each touching pair, a sphere at the centre of its contact and an arrow of the force on
/// the body there (0.02 m per N: contact forces are larger than the loads they carry), in the
/// namespace "contacts".
void appendContactMarkers(const std::vector<core::ContactPair>& pairs,
                          const std_msgs::Header& header, visualization_msgs::MarkerArray& array);

}  // namespace deformable_sim::ros_layer
