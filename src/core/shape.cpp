#include "deformable_sim/core/shape.h"

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
  }
}

double signedDistance(const Shape& shape, const Eigen::Vector3d& p, Eigen::Vector3d* surface,
                      Eigen::Vector3d* normal) {
  Eigen::Vector3d s, n;
  double distance = 0.0;
  switch (shape.kind) {
    case Shape::Kind::kSphere: {
      const double r = p.norm();
      n = r > 0.0 ? Eigen::Vector3d(p / r) : Eigen::Vector3d::UnitZ();
      s = shape.radius * n;
      distance = r - shape.radius;
      break;
    }
    case Shape::Kind::kBox: {
      const Eigen::Vector3d half = 0.5 * shape.size;
      const Eigen::Vector3d q = p.cwiseAbs() - half;
      if ((q.array() <= 0.0).all()) {
        // Inside: leave through the nearest face.
        int axis = 0;
        q.maxCoeff(&axis);
        n = Eigen::Vector3d::Zero();
        n[axis] = p[axis] < 0.0 ? -1.0 : 1.0;
        s = p;
        s[axis] = n[axis] * half[axis];
        distance = q[axis];
      } else {
        s = p.cwiseMax(-half).cwiseMin(half);
        distance = (p - s).norm();
        n = (p - s) / distance;
      }
      break;
    }
    case Shape::Kind::kCylinder: {
      const double half = 0.5 * shape.length;
      const Eigen::Vector2d xy = p.head<2>();
      const double rho = xy.norm();
      const Eigen::Vector2d radial =
          rho > 0.0 ? Eigen::Vector2d(xy / rho) : Eigen::Vector2d::UnitX();
      const double dr = rho - shape.radius, dz = std::abs(p.z()) - half;
      const double side = p.z() < 0.0 ? -1.0 : 1.0;
      if (dr <= 0.0 && dz <= 0.0) {
        s = p;
        if (dr > dz) {  // nearer the curved side
          s.head<2>() = shape.radius * radial;
          n << radial, 0.0;
          distance = dr;
        } else {
          s.z() = side * half;
          n = side * Eigen::Vector3d::UnitZ();
          distance = dz;
        }
      } else {
        s.head<2>() = std::min(rho, shape.radius) * radial;
        s.z() = std::clamp(p.z(), -half, half);
        distance = (p - s).norm();
        n = (p - s) / distance;
      }
      break;
    }
  }
  if (surface) *surface = s;
  if (normal) *normal = n;
  return distance;
}

}  // namespace deformable_sim::core
