// Scenes for the core's tests, said in a line each instead of a field at a time: what a test
// sets is what it is about, the rest keeps SceneSpec's defaults.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <utility>

#include "deformable_sim/core/contact/contact.h"
#include "deformable_sim/core/geometry/shape.h"
#include "deformable_sim/core/session/scene.h"

namespace deformable_sim::test {

/// A body whose mesh is the box [min, max] cut into `cells`.
inline core::BodySpec boxBody(const std::string& name, const Eigen::Vector3d& min,
                              const Eigen::Vector3d& max, const Eigen::Vector3i& cells,
                              const core::LinearElasticMaterial& material,
                              core::BodyModel model = core::BodyModel::kFiniteElement) {
  core::BodySpec body;
  body.name = name;
  body.model = model;
  body.box_mesh = core::BoxMeshSpec{min, max, cells};
  body.material = material;
  return body;
}

/// A box obstacle of edge lengths `size` whose top face is at z = 0, turned by `tilt` about the
/// world's x axis (a slope through the origin).
inline core::PlacedShape floorBox(const Eigen::Vector3d& size, const std::string& name = "floor",
                                  double tilt = 0.0) {
  core::PlacedShape floor;
  floor.name = name;
  floor.shape.kind = core::Shape::Kind::kBox;
  floor.shape.size = size;
  // At no tilt the rotation is the identity to the bit: the floor is where the plain one is.
  floor.pose.linear() = Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX()).toRotationMatrix();
  floor.pose.translation() = floor.pose.linear() * Eigen::Vector3d(0, 0, -0.5 * size.z());
  return floor;
}

/// A SceneSpec built a setting at a time: SceneBuilder().warped().gravity().floor({1, 1, 0.1}).
class SceneBuilder {
 public:
  SceneBuilder& dt(double dt) {
    spec_.dt = dt;
    return *this;
  }
  /// Gravity g down -z, m/s^2.
  SceneBuilder& gravity(double g = 9.81) { return gravity(Eigen::Vector3d(0, 0, -g)); }
  SceneBuilder& gravity(const Eigen::Vector3d& g) {
    spec_.effects.gravity = g;
    return *this;
  }
  /// Corotational (warped) stiffness.
  SceneBuilder& warped(bool on = true) {
    spec_.effects.warping = on;
    return *this;
  }
  /// Rayleigh damping: alpha (mass), beta (stiffness).
  SceneBuilder& damping(double mass, double stiffness) {
    return damping(core::RayleighDamping{mass, stiffness});
  }
  SceneBuilder& damping(const core::RayleighDamping& damping) {
    spec_.effects.damping = damping;
    return *this;
  }
  SceneBuilder& contact(double friction, bool bodies = false, bool self = false) {
    spec_.contact = core::ContactSettings{friction, bodies, self};
    return *this;
  }
  SceneBuilder& solver(core::SolverSettings::Method method) {
    spec_.solver.method = method;
    return *this;
  }
  SceneBuilder& obstacle(core::PlacedShape shape) {
    spec_.obstacles.push_back(std::move(shape));
    return *this;
  }
  /// A box obstacle of edge lengths `size` whose top is at z = 0 (floorBox).
  SceneBuilder& floor(const Eigen::Vector3d& size, const std::string& name = "floor",
                      double tilt = 0.0) {
    return obstacle(floorBox(size, name, tilt));
  }
  SceneBuilder& body(core::BodySpec body) {
    spec_.bodies.push_back(std::move(body));
    return *this;
  }
  /// A body whose mesh is the box [min, max] cut into `cells` (boxBody).
  SceneBuilder& box(const std::string& name, const Eigen::Vector3d& min, const Eigen::Vector3d& max,
                    const Eigen::Vector3i& cells, const core::LinearElasticMaterial& material,
                    core::BodyModel model = core::BodyModel::kFiniteElement) {
    return body(boxBody(name, min, max, cells, material, model));
  }

  const core::SceneSpec& spec() const { return spec_; }
  operator core::SceneSpec() const { return spec_; }  // NOLINT: reads as the spec it builds

 private:
  core::SceneSpec spec_;
};

/// The contact tests' table top: 0.01 s steps, gravity, warping, light damping (alpha 2 /s,
/// beta 2 ms), contact with `friction`, and a box table of `size` (top at z = 0) named "table".
inline SceneBuilder dampedTable(double friction, const Eigen::Vector3d& size) {
  SceneBuilder builder;
  builder.dt(0.01)
      .gravity(9.81)
      .warped()
      .damping(2.0, 0.002)
      .contact(friction)
      .floor(size, "table");
  return builder;
}

}  // namespace deformable_sim::test
