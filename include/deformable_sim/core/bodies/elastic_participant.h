// A finite-element body in contact between bodies: it answers an impulse as its implicit step
// would have (core/bodies/implicit_response.h; constrained nodes not at all), the answers gathered
// apart and added to its state once the contact is resolved.
#pragma once

#include "deformable_sim/core/bodies/contact_participant.h"
#include "deformable_sim/core/bodies/implicit_response.h"

namespace deformable_sim::core {

class ElasticParticipant : public ContactParticipant {
 public:
  explicit ElasticParticipant(FiniteElementBody& body);

  void begin(double dt, bool new_step = true) override;
  void end() override;
  double largestMove() const override { return largest_move_; }
  Eigen::Vector3d position(const SurfacePoint& point) const override;
  Eigen::Vector3d velocity(const SurfacePoint& point) const override;
  double inverseMass(const SurfacePoint& point, const Eigen::Vector3d& normal) const override;
  Eigen::Matrix3d compliance(const SurfacePoint& point, bool local = false,
                             int kept = -1) const override;
  Eigen::Matrix3d coupling(const SurfacePoint& at, const SurfacePoint& from,
                           int from_kept = -1) const override;
  int solves() const override { return response_.solves(); }
  void push(const SurfacePoint& point, const Eigen::Vector3d& impulse, bool local = false,
            int kept = -1) override;
  /// Sums the answers of a point of more than kFewNodes nodes (a vertex or triangle of a surface
  /// a body was made from: 8 or 24).
  int keep(const SurfacePoint& point) override;
  static constexpr int kFewNodes = 4;
  int keepCorner(int id, const SurfacePoint& point) override;
  int keepSum(const int* kept, const double* weights, int count) override {
    return response_.keepSum(kept, weights, count);
  }
  void nudge(const SurfacePoint& point, const Eigen::Vector3d& shift) override;
  double nudgeCompliance(const SurfacePoint& point, const Eigen::Vector3d& normal) const override;
  double movable(const SurfacePoint& point) const override;

 private:
  /// `amount` at the point, answered by its nodes alone (lumped masses; a point that shifts its
  /// cells, by them as one mass), added to `state`.
  void addLumped(const SurfacePoint& point, const Eigen::Vector3d& amount,
                 Eigen::VectorXd& state) const;
  /// The mass of the point's free nodes (a point that shifts its cells moves them as one).
  double clusterMass(const SurfacePoint& point) const;

  FiniteElementBody* body_;
  Eigen::VectorXd* x_ = nullptr;  ///< the body's own state, changed in place
  Eigen::VectorXd* v_ = nullptr;
  double dt_ = 0.0;            ///< of the step
  double largest_move_ = 0.0;  ///< m: see largestMove()
  /// Columns solved lazily, so `mutable`; it gathers the impulses of the whole-body answers.
  mutable ImplicitResponse response_;
  Eigen::VectorXd velocity_change_of_nodes_;  ///< their change of every node, made in end()
  Eigen::VectorXd round_start_;  ///< the positions at begin(), to measure largestMove()
};

}  // namespace deformable_sim::core
