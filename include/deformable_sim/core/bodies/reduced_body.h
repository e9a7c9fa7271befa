// A rigid or pseudo-rigid body: its nodes follow a few coordinates (core/bodies/reduced_dynamics.h)
// and are computed only when asked for, so that a step costs the same for any mesh.
#pragma once

#include "deformable_sim/core/bodies/body.h"
#include "deformable_sim/core/bodies/reduced_dynamics.h"

namespace deformable_sim::core {

class ReducedBody : public Body {
 public:
  /// `model` is kRigid or kPseudoRigid. Validates the material and the mesh
  /// (std::invalid_argument); integrates the mass properties, allocates nothing per element.
  ReducedBody(std::string name, Mesh mesh, const LinearElasticMaterial& material,
              const BodyEffects& effects, const SolverSettings& solver, BodyModel model);

  StepReport step(double dt) override;
  double kineticEnergy() const override { return reduced_.kineticEnergy(); }
  double elasticEnergy() const override { return reduced_.elasticEnergy(); }
  bool stateIsFinite() const override { return reduced_.finite(); }
  void undoStep() override;
  std::unique_ptr<ContactParticipant> contactParticipant() override;

  const ReducedDynamics& reduced() const { return reduced_; }
  /// Changes the centre, the gradient and their rates by the given amounts (contact between
  /// bodies gathers them); a rigid body's gradient stays a rotation.
  void moveBy(const Eigen::Vector3d& centre, const Eigen::Matrix3d& gradient,
              const Eigen::Vector3d& velocity, const Eigen::Matrix3d& gradient_rate);
  /// How often the nodes were computed from the coordinates, and the nodal forces summed into a
  /// resultant. Neither happens in a step, only when asked for or changed.
  long nodeUpdates() const { return node_updates_; }
  long loadSums() const { return load_sums_; }

 protected:
  void changeMaterial(const LinearElasticMaterial& material) override;
  void assignState(const Eigen::VectorXd& positions, const Eigen::VectorXd& velocities) override;
  StaticReport solveStaticChecked(const StaticSettings& settings) override;
  void holdChanged(int node, bool held) override;
  void updateNodes() const override;

 private:
  /// Sums the external forces into load_resultant_ if they may have changed.
  void sumLoads();
  NodeConstraints nodeConstraints() const {
    return NodeConstraints{&constrained_nodes_, &x0_, &targets_};
  }

  ReducedDynamics reduced_;
  LoadResultant load_resultant_;        ///< external forces summed, when they change
  std::vector<int> constrained_nodes_;  ///< ascending
  mutable long node_updates_ = 0;
  long load_sums_ = 0;
};

}  // namespace deformable_sim::core
