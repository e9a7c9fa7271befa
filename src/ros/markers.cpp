#include "deformable_sim/ros/markers.h"

#include <algorithm>
#include <utility>

#include "deformable_sim/core/outputs/body_colours.h"
#include "deformable_sim/core/outputs/drawn_interactions.h"
#include "deformable_sim/ros/conversions.h"

namespace deformable_sim::ros_layer {

namespace {

std_msgs::ColorRGBA rgba(float r, float g, float b, float a = 1.0f) {
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

visualization_msgs::Marker marker(const std_msgs::Header& header, const std::string& ns, int id,
                                  int type, double scale, const std_msgs::ColorRGBA& c) {
  visualization_msgs::Marker m;
  m.header = header;
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.scale.x = m.scale.y = m.scale.z = scale;
  m.color = c;
  return m;
}

// Blue at no strain to red at `scale` and above.
std_msgs::ColorRGBA strainColour(double strain, double scale) {
  const float s = static_cast<float>(std::clamp(strain / scale, 0.0, 1.0));
  return rgba(s, 0.2f, 1.0f - s);
}

}  // namespace

SurfaceMarkers::SurfaceMarkers(const core::Simulation& simulation, double strain_scale,
                               std::vector<Eigen::Vector3d> colours, double lifetime_s)
    : surfaces_(simulation),
      strain_scale_(strain_scale),
      colours_(std::move(colours)),
      lifetime_s_(lifetime_s) {}

const visualization_msgs::Marker& SurfaceMarkers::marker(const core::Body& body, int index,
                                                         const std_msgs::Header& header) {
  surfaces_.update(body, index);
  const std::vector<Eigen::Vector3d>& corners = surfaces_.corners();
  const std::vector<double>& strains = surfaces_.strains();
  visualization_msgs::Marker& m = marker_;
  m.header = header;
  m.ns = body.name();
  m.id = 0;
  m.type = visualization_msgs::Marker::TRIANGLE_LIST;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.scale.x = m.scale.y = m.scale.z = 1.0;
  const Eigen::Vector3d colour =
      index < static_cast<int>(colours_.size()) ? colours_[index] : core::paletteColour(index);
  m.color = rgba(static_cast<float>(colour.x()), static_cast<float>(colour.y()),
                 static_cast<float>(colour.z()));
  m.lifetime = ros::Duration(lifetime_s_);
  m.points.resize(corners.size());
  for (size_t c = 0; c < corners.size(); ++c) m.points[c] = toPoint(corners[c]);
  m.colors.resize(strains.size());
  for (size_t c = 0; c < strains.size(); ++c) m.colors[c] = strainColour(strains[c], strain_scale_);
  return m;
}

visualization_msgs::Marker deleteAllMarker(const std_msgs::Header& header) {
  visualization_msgs::Marker marker;
  marker.header = header;
  marker.action = visualization_msgs::Marker::DELETEALL;
  marker.pose.orientation.w = 1.0;
  return marker;
}

visualization_msgs::MarkerArray interactionMarkers(const core::BodyList& bodies,
                                                   const core::CommandProcessor& commands,
                                                   const std_msgs::Header& header) {
  using visualization_msgs::Marker;
  const core::DrawnInteractions drawn = core::drawnInteractions(bodies, commands, 0.1);
  visualization_msgs::MarkerArray array;
  array.markers.push_back(deleteAllMarker(header));
  const auto add = [&array](Marker m, const std::vector<Eigen::Vector3d>& points) {
    for (const Eigen::Vector3d& p : points) m.points.push_back(toPoint(p));
    if (!m.points.empty()) array.markers.push_back(m);
  };
  for (size_t b = 0; b < bodies.size(); ++b) {
    const std::string& name = bodies[b].name();
    const core::DrawnNodes& nodes = drawn.bodies[b];
    add(marker(header, name + "/grasped", 0, Marker::SPHERE_LIST, 0.012, rgba(0.95f, 0.85f, 0.1f)),
        nodes.grasped);
    add(marker(header, name + "/fixed", 0, Marker::SPHERE_LIST, 0.015, rgba(0.9f, 0.1f, 0.1f)),
        nodes.fixed);
    int id = 0;
    for (const auto& [group, points] : nodes.groups) {
      add(marker(header, name + "/groups", id++, Marker::POINTS, 0.01, rgba(0.1f, 0.3f, 0.9f)),
          points);
    }
  }
  int id = 0;
  for (const core::DrawnArrow& wrench : drawn.wrenches) {
    Marker arrow = marker(header, "wrenches", id++, Marker::ARROW, 0.0, rgba(0.1f, 0.8f, 0.2f));
    arrow.scale.x = 0.01;  // shaft diameter
    arrow.scale.y = 0.02;  // head diameter
    add(arrow, {wrench.from, wrench.to});
  }
  return array;
}

void appendContactMarkers(const std::vector<core::ContactPair>& pairs,
                          const std_msgs::Header& header, visualization_msgs::MarkerArray& array) {
  if (pairs.empty()) return;
  visualization_msgs::Marker centres =
      marker(header, "contacts", 0, visualization_msgs::Marker::SPHERE_LIST, 0.012,
             rgba(0.9f, 0.4f, 0.9f));
  int id = 1;
  for (const core::ContactPair& pair : pairs) {
    centres.points.push_back(toPoint(pair.load.centre));
    if (pair.load.force.isZero(0.0)) continue;
    visualization_msgs::Marker arrow = marker(
        header, "contacts", id++, visualization_msgs::Marker::ARROW, 0.0, rgba(0.9f, 0.4f, 0.9f));
    arrow.scale.x = 0.005;  // shaft diameter
    arrow.scale.y = 0.01;   // head diameter
    arrow.points.push_back(toPoint(pair.load.centre));
    arrow.points.push_back(toPoint(pair.load.centre + 0.02 * pair.load.force));
    array.markers.push_back(arrow);
  }
  array.markers.push_back(centres);
}

}  // namespace deformable_sim::ros_layer
