// A rigid or pseudo-rigid body in contact between bodies: it answers an impulse with its whole
// motion (its mass and inertia, or its mass and Euler tensor), gathered in increments of its
// coordinates and handed to it once the contact is resolved. The two differ only in how an
// impulse at an arm turns (rigid) or strains (pseudo-rigid) the body.
#pragma once

#include "deformable_sim/core/bodies/contact_participant.h"
#include "deformable_sim/core/bodies/reduced_body.h"

namespace deformable_sim::core {

class WholeBodyParticipant : public ContactParticipant {
 public:
  explicit WholeBodyParticipant(ReducedBody& body);

  void begin(double dt, bool new_step = true) override;
  void end() override;
  Eigen::Vector3d position(const SurfacePoint& point) const override;
  Eigen::Vector3d velocity(const SurfacePoint& point) const override;
  Eigen::Matrix3d coupling(const SurfacePoint& at, const SurfacePoint& from,
                           int from_kept = -1) const override;
  void push(const SurfacePoint& point, const Eigen::Vector3d& impulse, bool local = false,
            int kept = -1) override;
  void nudge(const SurfacePoint& point, const Eigen::Vector3d& shift) override;
  double nudgeCompliance(const SurfacePoint& point, const Eigen::Vector3d& normal) const override {
    return inverseMass(point, normal);
  }
  double movable(const SurfacePoint&) const override { return 1.0; }

 protected:
  /// The inverse of what resists the gradient's change: the world inverse inertia (rigid) or the
  /// inverse Euler tensor (pseudo-rigid), for the body's present gradient.
  virtual Eigen::Matrix3d inverseMoment(const MassProperties& mass) const = 0;
  /// How the gradient (or its rate) changes when `amount` acts at the rest arm `a`.
  virtual Eigen::Matrix3d gradientChange(const Eigen::Vector3d& a,
                                         const Eigen::Vector3d& amount) const = 0;

  /// The rest arm X - Xc of the point.
  Eigen::Vector3d arm(const SurfacePoint& point) const;

  Eigen::Matrix3d gradient_ = Eigen::Matrix3d::Identity();
  /// Rigid: the inverse inertia in the world frame; pseudo-rigid: the inverse Euler tensor.
  Eigen::Matrix3d inverse_moment_ = Eigen::Matrix3d::Identity();
  double inverse_mass_ = 0.0;  ///< of the whole body; 0 while a node holds it

 private:
  ReducedBody* body_;
  double dt_ = 0.0;  ///< of the step
  Eigen::Vector3d rest_centre_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d centre_change_ = Eigen::Vector3d::Zero(),
                  velocity_change_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d gradient_change_ = Eigen::Matrix3d::Zero(),
                  rate_change_ = Eigen::Matrix3d::Zero();
  Eigen::VectorXd base_x_, base_v_;  ///< the nodes after the step
};

class RigidParticipant : public WholeBodyParticipant {
 public:
  using WholeBodyParticipant::WholeBodyParticipant;
  double inverseMass(const SurfacePoint& point, const Eigen::Vector3d& normal) const override;

 protected:
  Eigen::Matrix3d inverseMoment(const MassProperties& mass) const override;
  Eigen::Matrix3d gradientChange(const Eigen::Vector3d& a,
                                 const Eigen::Vector3d& amount) const override;
};

class PseudoRigidParticipant : public WholeBodyParticipant {
 public:
  using WholeBodyParticipant::WholeBodyParticipant;
  double inverseMass(const SurfacePoint& point, const Eigen::Vector3d& normal) const override;

 protected:
  Eigen::Matrix3d inverseMoment(const MassProperties& mass) const override;
  Eigen::Matrix3d gradientChange(const Eigen::Vector3d& a,
                                 const Eigen::Vector3d& amount) const override;
};

}  // namespace deformable_sim::core
