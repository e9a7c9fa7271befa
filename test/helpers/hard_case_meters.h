// What the hard cases (test_hard_*.cpp, DESIGN.md section 8) share: their scenes, the step
// that checks what every case must keep, and the meters of shape, volume, momentum and energy.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "body_meters.h"
#include "deformable_sim/core/bodies/rigid_frame.h"
#include "deformable_sim/core/elements/corotational_elasticity.h"
#include "deformable_sim/core/elements/selection.h"
#include "deformable_sim/core/outputs/strain.h"
#include "deformable_sim/core/session/simulation.h"
#include "scene_builder.h"
#include "simulation_test_helpers.h"

namespace deformable_sim::test::hard_cases {

// The shared helpers the cases use, so that one using-directive brings the cases' whole vocabulary.
using test::boxBody;
using test::boxMeshSimulation;
using test::boxSelection;
using test::centreOfMass;
using test::momentum;
using test::SceneBuilder;
using test::totalMass;

inline const Eigen::Vector3d kGravity(0.0, 0.0, -9.81);
inline const core::LinearElasticMaterial kRubber{1.0e6, 0.3, 1000.0};
/// The built-in scene's damping (core/session/default_scene.h), for the cases that must come to
/// rest.
inline const core::RayleighDamping kSceneDamping{1.0, 0.002};

/// A scene as a user gets it (SceneSpec's dt, solver and no damping) with the corotational
/// elasticity these cases are about.
inline core::SceneSpec warpedScene() { return SceneBuilder().warped(); }

/// The nodes whose rest x lies at `x` (a beam's end face).
inline core::NodeSelection faceAtX(double x) {
  return boxSelection({x - 1e-9, -1e3, -1e3}, {x + 1e-9, 1e3, 1e3});
}

/// A beam of 10 x 2 x 2 cells along x from x = 0, clamped there.
inline core::BodySpec clampedBeam(const std::string& name, const Eigen::Vector3d& min,
                                  const Eigen::Vector3d& max,
                                  const core::LinearElasticMaterial& material) {
  core::BodySpec beam = boxBody(name, min, max, {10, 2, 2}, material);
  beam.fixed.push_back(faceAtX(0.0));
  return beam;
}

/// The simulation of `spec` with one body: a rubber beam 0.5 m long, 10 cm square, clamped at
/// x = 0 (the beam the twist, the impulse and the teleport load).
inline core::Simulation clampedRubberBeam(core::SceneSpec spec) {
  spec.bodies.push_back(clampedBeam("beam", {0, -0.05, -0.05}, {0.5, 0.05, 0.05}, kRubber));
  return boxMeshSimulation(spec);
}

/// warpedScene() with gravity and the built-in scene's damping: bodies sag and come to rest.
inline core::SceneSpec settlingScene() {
  return SceneBuilder().warped().gravity(kGravity).damping(kSceneDamping);
}

inline bool finite(const core::Body& body) {
  return body.positions().allFinite() && body.velocities().allFinite();
}

inline Eigen::Vector3d node(const Eigen::VectorXd& stacked, int i) {
  return stacked.segment<3>(3 * i);
}

/// Largest distance of a node from the best-fit rigid motion of the rest shape, m: zero for any
/// rigidly moved rest shape.
inline double distanceFromRestShape(const core::Body& body) {
  const core::RigidFrame frame =
      core::bestFitFrame(body.positions(), body.restPositions(), body.nodalMasses());
  double largest = 0.0;
  for (int i = 0; i < body.numNodes(); ++i) {
    const Eigen::Vector3d fitted =
        frame.origin + frame.rotation * (node(body.restPositions(), i) - frame.rest_origin);
    largest = std::max(largest, (node(body.positions(), i) - fitted).norm());
  }
  return largest;
}

/// Largest distance of a node from its rest position, m.
inline double distanceFromRest(const core::Body& body) {
  double largest = 0.0;
  for (int i = 0; i < body.numNodes(); ++i) {
    largest = std::max(largest, (node(body.positions(), i) - node(body.restPositions(), i)).norm());
  }
  return largest;
}

inline double largestStrain(const core::Body& body) {
  std::vector<double> strain;
  core::nodalStrain(body, strain);
  return *std::max_element(strain.begin(), strain.end());
}

inline double smallestVolume(const core::Body& body) {
  std::vector<Eigen::Vector3d> x(body.numNodes());
  for (int i = 0; i < body.numNodes(); ++i) x[i] = node(body.positions(), i);
  double smallest = INFINITY;
  for (const core::Tetrahedron& t : body.mesh().tetrahedra)
    smallest = std::min(smallest, core::signedVolume(x, t));
  return smallest;
}

inline double currentVolume(const core::Body& body) {
  core::Mesh deformed = body.mesh();
  for (int i = 0; i < body.numNodes(); ++i) deformed.positions[i] = node(body.positions(), i);
  return core::totalVolume(deformed);
}

/// About the centre of mass, kg m^2/s.
inline Eigen::Vector3d angularMomentum(const core::Body& body) {
  const Eigen::Vector3d c = centreOfMass(body);
  Eigen::Vector3d l = Eigen::Vector3d::Zero();
  for (int i = 0; i < body.numNodes(); ++i) {
    l += body.nodalMasses()[i] * (node(body.positions(), i) - c).cross(node(body.velocities(), i));
  }
  return l;
}

/// Kinetic + elastic + gravitational energy relative to the rest state, J. The meter has its own
/// elements and takes the rotations of the positions it measures, whatever the body computed.
class EnergyMeter {
 public:
  explicit EnergyMeter(const core::Body& body)
      : elasticity_(body.mesh(), body.settings().material),
        gravity_(body.settings().effects.gravity) {}

  double elastic(const core::Body& body) {
    elasticity_.updateRotations(body.positions());
    return elasticity_.elasticEnergy(body.positions());
  }

  double total(const core::Body& body) {
    double energy = body.kineticEnergy() + elastic(body);
    if (gravity_) {
      for (int i = 0; i < body.numNodes(); ++i) {
        energy -= body.nodalMasses()[i] *
                  gravity_->dot(node(body.positions(), i) - node(body.restPositions(), i));
      }
    }
    return energy;
  }

 private:
  core::CorotationalElasticity elasticity_;
  std::optional<Eigen::Vector3d> gravity_;
};

/// Work of the nodal forces f (constant over the step) from x_before to the body's positions, J.
inline double work(const Eigen::VectorXd& f, const Eigen::VectorXd& x_before,
                   const core::Body& body) {
  return f.dot(body.positions() - x_before);
}

/// Steps the simulation once and checks what every hard case must keep: finite values, a step
/// the watchdog did not have to undo.
inline void stepChecked(core::Simulation& sim, std::vector<core::StepReport>& reports, int step) {
  sim.step(reports);
  for (size_t b = 0; b < sim.bodies().size(); ++b) {
    ASSERT_TRUE(finite(sim.bodies()[b])) << sim.bodies()[b].name() << " step " << step;
    ASSERT_FALSE(reports[b].recovered) << sim.bodies()[b].name() << " step " << step;
  }
}

/// The largest rise of an energy from one step to the next, J: zero for a body that only loses
/// energy.
struct EnergyLog {
  double previous = 0.0;
  double largest_rise = 0.0;
  void start(double energy) { previous = energy; }
  void add(double energy) {
    largest_rise = std::max(largest_rise, energy - previous);
    previous = energy;
  }
};

}  // namespace deformable_sim::test::hard_cases
