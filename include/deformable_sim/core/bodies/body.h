// A body of a scene as everything above the bodies sees it: its mesh and settings, its state,
// the nodes it holds and the loads on it, its step and static solve, and how it answers an
// impulse within a step. Each model is one class behind this interface, made by makeBody(), the
// one place that picks a body's class: finite elements (core/bodies/finite_element_body.h) and
// the reduced rigid and pseudo-rigid bodies (core/bodies/reduced_body.h), which tell their two
// kinds of coordinates apart themselves.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "deformable_sim/core/bodies/body_effects.h"
#include "deformable_sim/core/bodies/step_report.h"
#include "deformable_sim/core/elements/material.h"
#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/core/solvers/linear_solver.h"

namespace deformable_sim::core {

class ContactParticipant;
class FiniteElementBody;

/// What a body is made of and how it is solved, as the scene gives it.
struct BodySettings {
  BodyModel model = BodyModel::kFiniteElement;
  LinearElasticMaterial material;
  BodyEffects effects;
  SolverSettings solver;
};

/// A change of settings between steps (live tuning); what is unset stays as it is.
struct BodyTuning {
  std::optional<LinearElasticMaterial> material;
  std::optional<RayleighDamping> damping;
  std::optional<double> solver_tolerance;
  std::optional<int> solver_max_iterations;
};

class Body {
 public:
  virtual ~Body();
  Body(const Body&) = delete;
  Body& operator=(const Body&) = delete;

  const std::string& name() const { return name_; }
  /// Its nodes, elements and named node groups.
  const Mesh& mesh() const { return mesh_; }
  const BodySettings& settings() const { return settings_; }
  const EffectCounters& effectCounters() const { return counters_; }
  /// Changes material (element stiffnesses and masses recomputed in place, the pattern kept),
  /// damping and solver limits between steps. Checks all first: throws std::invalid_argument and
  /// changes nothing for a bad value.
  void tune(const BodyTuning& tuning);

  int numNodes() const { return mesh_.numNodes(); }
  /// Stacked 3n vectors: positions (m), velocities (m/s), rest positions (m). A reduced body
  /// computes its nodes here, on the first call after a step.
  const Eigen::VectorXd& positions() const {
    if (nodes_stale_) updateNodes();
    return x_;
  }
  const Eigen::VectorXd& velocities() const {
    if (nodes_stale_) updateNodes();
    return v_;
  }
  const Eigen::VectorXd& restPositions() const { return x0_; }
  const std::vector<double>& nodalMasses() const { return mass_; }  ///< kg
  /// Replaces the state (sizes must match); e.g. to start from a given deformation. A reduced
  /// body takes the motion of its model that fits them best (least squares).
  void setState(const Eigen::VectorXd& positions, const Eigen::VectorXd& velocities);
  virtual double kineticEnergy() const = 0;  ///< J
  /// J; a finite-element body's with the element rotations of the present positions.
  virtual double elasticEnergy() const = 0;

  /// Holds the nodes where they are now (v = 0).
  void fixNodes(const std::vector<int>& nodes);
  /// Prescribes where the nodes are at the end of the next step (v = (target - x) / h); they stay
  /// there afterwards until given another target or released.
  void setNodeTargets(const std::vector<int>& nodes, const std::vector<Eigen::Vector3d>& targets);
  /// Returns the nodes to free motion.
  void releaseNodes(const std::vector<int>& nodes);
  bool isConstrained(int node) const { return constrained_[node] != 0; }

  /// Applied nodal forces (3n, N); they persist from step to step until changed. Write them
  /// through the reference before the next step: a reduced body sums them then (do not keep the
  /// reference across steps).
  Eigen::VectorXd& externalForces() {
    loads_stale_ = true;
    return external_forces_;
  }
  const Eigen::VectorXd& externalForces() const { return external_forces_; }
  /// Force each constraint exerts on its node in the last step or static solve (3n, N); zero at
  /// free nodes. Their sum balances the loads in equilibrium.
  const Eigen::VectorXd& reactionForces() const { return reaction_; }

  /// One implicit Euler step of dt s. The body keeps where it began, for undoStep().
  virtual StepReport step(double dt) = 0;
  /// Equilibrium under the external forces and gravity; leaves the body at rest there.
  StaticReport solveStatic(const StaticSettings& settings);
  /// For Simulation's watchdog: whether the state is finite; and back to where the last step
  /// began, at rest.
  virtual bool stateIsFinite() const = 0;
  virtual void undoStep() = 0;

  /// How the body answers impulses within its last step, for contact between bodies; allocates
  /// only here. The body must outlive it.
  virtual std::unique_ptr<ContactParticipant> contactParticipant() = 0;
  /// The body with its own elements (contact with obstacles acts on its nodes), or null.
  virtual FiniteElementBody* finiteElements() { return nullptr; }
  virtual const FiniteElementBody* finiteElements() const { return nullptr; }

 protected:
  /// Validates the material and the mesh (std::invalid_argument naming the body).
  Body(std::string name, Mesh mesh, const BodySettings& settings);
  /// A body of a model class may be returned by value before anything refers to it.
  Body(Body&&) = default;

  /// The model's part of tune() and setState(), after the checks.
  virtual void changeMaterial(const LinearElasticMaterial& material) = 0;
  virtual void assignState(const Eigen::VectorXd& positions, const Eigen::VectorXd& velocities) = 0;
  virtual StaticReport solveStaticChecked(const StaticSettings& settings) = 0;
  /// A node was held (true) or let go: the model updates what depends on the set of held nodes.
  virtual void holdChanged(int node, bool held) = 0;
  /// A reduced body's nodes from its coordinates.
  virtual void updateNodes() const {}
  /// "body 'name': " for error messages.
  std::string where() const { return "body '" + name_ + "': "; }

  std::string name_;
  Mesh mesh_;
  BodySettings settings_;
  EffectCounters counters_;
  Eigen::VectorXd x0_;
  mutable Eigen::VectorXd x_, v_;  ///< of a reduced body: computed when asked for
  mutable bool nodes_stale_ = false;
  std::vector<double> mass_;
  ConstraintMask constrained_;
  Eigen::VectorXd targets_;  ///< prescribed positions of constrained nodes
  Eigen::VectorXd external_forces_;
  bool loads_stale_ = true;  ///< a reduced body sums them again before its next step
  Eigen::VectorXd reaction_;
};

/// Nodes held (fixed, or moving to a target).
int numConstrained(const Body& body);

/// The body of `settings.model`; validates as the body's constructor does.
std::unique_ptr<Body> makeBody(std::string name, Mesh mesh, const BodySettings& settings);

}  // namespace deformable_sim::core
