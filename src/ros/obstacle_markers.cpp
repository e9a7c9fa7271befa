#include "deformable_sim/ros/obstacle_markers.h"

#include <tf2_eigen/tf2_eigen.h>

#include <algorithm>

#include "deformable_sim/ros/conversions.h"
#include "deformable_sim/ros/markers.h"

namespace deformable_sim::ros_layer {

namespace {

using visualization_msgs::Marker;

// Sets the type and scale of `m` for a box, sphere or cylinder (URDF's conventions are rviz's).
void setPrimitive(const core::Shape& shape, Marker& m) {
  switch (shape.kind) {
    case core::Shape::Kind::kBox:
      m.type = Marker::CUBE;
      m.scale = toVector3(shape.size);
      break;
    case core::Shape::Kind::kSphere:
      m.type = Marker::SPHERE;
      m.scale = toVector3(Eigen::Vector3d::Constant(2.0 * shape.radius));
      break;
    default:
      m.type = Marker::CYLINDER;
      m.scale = toVector3(Eigen::Vector3d(2.0 * shape.radius, 2.0 * shape.radius, shape.length));
      break;
  }
}

// The file when there is one (rviz loads it), else the triangles as read (already scaled).
void setMesh(const core::Shape& shape, Marker& m) {
  if (!shape.mesh_uri.empty()) {
    m.type = Marker::MESH_RESOURCE;
    m.mesh_resource = shape.mesh_uri;
    m.mesh_use_embedded_materials = false;
    m.scale = toVector3(shape.mesh_scale);
    return;
  }
  m.type = Marker::TRIANGLE_LIST;
  m.scale = toVector3(Eigen::Vector3d::Ones());
  if (!shape.mesh) return;
  const core::TriangleMesh& mesh = shape.mesh->mesh();
  for (const Eigen::Vector3i& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) m.points.push_back(toPoint(mesh.vertices[t[k]]));
  }
}

}  // namespace

visualization_msgs::MarkerArray obstacleMarkers(const std::vector<core::PlacedShape>& obstacles,
                                                const std_msgs::Header& header,
                                                const std::vector<std::string>& links) {
  visualization_msgs::MarkerArray array;
  array.markers.push_back(deleteAllMarker(header));
  for (size_t k = 0; k < obstacles.size(); ++k) {
    const core::PlacedShape& obstacle = obstacles[k];
    Marker m;
    m.header = header;
    const bool link = std::find(links.begin(), links.end(), obstacle.name) != links.end();
    m.ns = link ? "links" : "obstacles";
    m.id = static_cast<int>(k);
    m.action = Marker::ADD;
    m.pose = tf2::toMsg(obstacle.pose);
    m.color.r = m.color.g = m.color.b = 0.6f;
    m.color.a = 1.0f;
    if (obstacle.shape.kind == core::Shape::Kind::kMesh) {
      setMesh(obstacle.shape, m);
    } else {
      setPrimitive(obstacle.shape, m);
    }
    array.markers.push_back(m);
  }
  return array;
}

}  // namespace deformable_sim::ros_layer
