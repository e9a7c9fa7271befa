#include "deformable_sim/core/geometry/shape.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace deformable_sim::core {

namespace {

bool positiveFinite(double value) { return value > 0.0 && std::isfinite(value); }

}  // namespace

void validate(const Shape& shape, const std::string& what) {
  switch (shape.kind) {
    case Shape::Kind::kBox:
      if (!(positiveFinite(shape.size.x()) && positiveFinite(shape.size.y()) &&
            positiveFinite(shape.size.z()))) {
        throw std::invalid_argument(what + ": a box needs three finite sizes > 0 m");
      }
      break;
    case Shape::Kind::kSphere:
      if (!positiveFinite(shape.radius)) {
        throw std::invalid_argument(what + ": a sphere needs a finite radius > 0 m");
      }
      break;
    case Shape::Kind::kCylinder:
      if (!positiveFinite(shape.radius) || !positiveFinite(shape.length)) {
        throw std::invalid_argument(what + ": a cylinder needs a finite radius and length > 0 m");
      }
      break;
    case Shape::Kind::kMesh:
      if (!shape.mesh) throw std::invalid_argument(what + ": a mesh shape needs its triangles");
      break;
  }
}

namespace {

// The nearest point of a shape's surface to p, its outward normal there, and p's signed distance
// from it (negative inside); all in the shape's frame.
struct SurfacePoint {
  double distance = 0.0;
  Eigen::Vector3d surface = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::Zero();
};

SurfacePoint nearestOnSphere(double radius, const Eigen::Vector3d& p) {
  SurfacePoint nearest;
  const double r = p.norm();
  nearest.normal = r > 0.0 ? Eigen::Vector3d(p / r) : Eigen::Vector3d::UnitZ();
  nearest.surface = radius * nearest.normal;
  nearest.distance = r - radius;
  return nearest;
}

SurfacePoint nearestOnBox(const Eigen::Vector3d& size, const Eigen::Vector3d& p) {
  SurfacePoint nearest;
  const Eigen::Vector3d half = 0.5 * size;
  const Eigen::Vector3d q = p.cwiseAbs() - half;
  if ((q.array() <= 0.0).all()) {
    // Inside: leave through the nearest face.
    int axis = 0;
    q.maxCoeff(&axis);
    nearest.normal = Eigen::Vector3d::Zero();
    nearest.normal[axis] = p[axis] < 0.0 ? -1.0 : 1.0;
    nearest.surface = p;
    nearest.surface[axis] = nearest.normal[axis] * half[axis];
    nearest.distance = q[axis];
  } else {
    nearest.surface = p.cwiseMax(-half).cwiseMin(half);
    nearest.distance = (p - nearest.surface).norm();
    nearest.normal = (p - nearest.surface) / nearest.distance;
  }
  return nearest;
}

// A cylinder along z, centred on the origin.
SurfacePoint nearestOnCylinder(double radius, double length, const Eigen::Vector3d& p) {
  SurfacePoint nearest;
  const double half = 0.5 * length;
  const Eigen::Vector2d xy = p.head<2>();
  const double rho = xy.norm();
  const Eigen::Vector2d radial = rho > 0.0 ? Eigen::Vector2d(xy / rho) : Eigen::Vector2d::UnitX();
  const double dr = rho - radius, dz = std::abs(p.z()) - half;
  const double side = p.z() < 0.0 ? -1.0 : 1.0;
  if (dr <= 0.0 && dz <= 0.0) {
    nearest.surface = p;
    if (dr > dz) {  // nearer the curved side
      nearest.surface.head<2>() = radius * radial;
      nearest.normal << radial, 0.0;
      nearest.distance = dr;
    } else {
      nearest.surface.z() = side * half;
      nearest.normal = side * Eigen::Vector3d::UnitZ();
      nearest.distance = dz;
    }
  } else {
    nearest.surface.head<2>() = std::min(rho, radius) * radial;
    nearest.surface.z() = std::clamp(p.z(), -half, half);
    nearest.distance = (p - nearest.surface).norm();
    nearest.normal = (p - nearest.surface) / nearest.distance;
  }
  return nearest;
}

}  // namespace

Eigen::AlignedBox3d bounds(const Shape& shape) {
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
  switch (shape.kind) {
    case Shape::Kind::kBox:
      half = 0.5 * shape.size;
      break;
    case Shape::Kind::kSphere:
      half.setConstant(shape.radius);
      break;
    case Shape::Kind::kCylinder:
      half = Eigen::Vector3d(shape.radius, shape.radius, 0.5 * shape.length);
      break;
    case Shape::Kind::kMesh:
      return shape.mesh->bounds();
  }
  return Eigen::AlignedBox3d(-half, half);
}

double signedDistance(const Shape& shape, const Eigen::Vector3d& p, Eigen::Vector3d* surface,
                      Eigen::Vector3d* normal) {
  SurfacePoint nearest;
  switch (shape.kind) {
    case Shape::Kind::kSphere:
      nearest = nearestOnSphere(shape.radius, p);
      break;
    case Shape::Kind::kBox:
      nearest = nearestOnBox(shape.size, p);
      break;
    case Shape::Kind::kCylinder:
      nearest = nearestOnCylinder(shape.radius, shape.length, p);
      break;
    case Shape::Kind::kMesh:
      return shape.mesh->signedDistance(p, surface, normal);
  }
  if (surface) *surface = nearest.surface;
  if (normal) *normal = nearest.normal;
  return nearest.distance;
}

}  // namespace deformable_sim::core
