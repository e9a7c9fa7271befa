// Solids for obstacles and grasp regions (boxes, spheres, cylinders as URDF has them, and triangle
// meshes), with the distance queries that contact and grasping need.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>

#include "deformable_sim/core/geometry/triangle_mesh_shape.h"

namespace deformable_sim::core {

/// A solid in its own frame: a box centred on the origin, a sphere around it, or a cylinder along
/// z centred on it (the URDF conventions), or a triangle mesh in its file's coordinates.
struct Shape {
  enum class Kind { kBox, kSphere, kCylinder, kMesh };
  Kind kind = Kind::kBox;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  ///< kBox: edge lengths, m
  double radius = 0.0;                             ///< kSphere, kCylinder: m
  double length = 0.0;                             ///< kCylinder: along z, m
  /// kMesh: shared, since the tree is built once and the shape is copied with every pose.
  std::shared_ptr<const TriangleMeshShape> mesh;
  /// kMesh: the file it was read from as a URI a viewer can load (package://, or file:// with an
  /// absolute path), and the scale applied to the file's coordinates; empty when it has no file.
  std::string mesh_uri;
  Eigen::Vector3d mesh_scale = Eigen::Vector3d::Ones();
};

/// Throws std::invalid_argument naming `what` unless every dimension is finite and > 0.
void validate(const Shape& shape, const std::string& what);

/// The smallest box, in the shape's own frame, that holds it.
Eigen::AlignedBox3d bounds(const Shape& shape);

/// Signed distance from `point` (in the shape's frame) to the shape's surface: negative inside.
/// Also the nearest surface point and the outward normal there (either may be null).
double signedDistance(const Shape& shape, const Eigen::Vector3d& point,
                      Eigen::Vector3d* surface = nullptr, Eigen::Vector3d* normal = nullptr);

/// A shape placed in the world.
struct PlacedShape {
  std::string name;  ///< e.g. the URDF link it belongs to
  Shape shape;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< shape frame in the world
};

/// The same shape in the same place, bit for bit.
inline bool operator==(const PlacedShape& a, const PlacedShape& b) {
  return a.name == b.name && a.shape.kind == b.shape.kind && a.shape.size == b.shape.size &&
         a.shape.radius == b.shape.radius && a.shape.length == b.shape.length &&
         a.shape.mesh == b.shape.mesh && a.pose.matrix() == b.pose.matrix();
}

}  // namespace deformable_sim::core
