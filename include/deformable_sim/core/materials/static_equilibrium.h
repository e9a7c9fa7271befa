// Static equilibrium of a hyperelastic mesh (materials/hyperelastic_elements.h) under dead nodal
// loads, with nodes held where they rest: the load is applied in increments, each solved by
// Newton's method on the total potential energy
//   Pi(x) = E(x) - s f . (x - X)        (s: the fraction of the load applied)
// with a backtracking line search on Pi, as CalculiX's *STATIC, NLGEOM does it on its
// residuals. Newton's matrix is the exact tangent where it is positive definite on the free
// nodes, else the tangent with each element's block projected (then the step still goes downhill).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "deformable_sim/core/materials/hyperelastic_elements.h"

namespace deformable_sim::core {

struct StaticSettings {
  int increments = 10;      ///< equal increments of the load from where it is to the target
  int max_iterations = 50;  ///< Newton iterations per increment at most
  /// The largest free nodal residual as a fraction of the largest nodal force in play.
  double tolerance = 1e-10;
};

struct StaticReport {
  int iterations = 0;      ///< Newton iterations over all increments
  int projected = 0;       ///< of which with the projected tangent
  double residual = 0.0;   ///< N: the largest free nodal residual at the end
  bool converged = false;  ///< every increment reached the tolerance
};

class StaticEquilibrium {
 public:
  /// `elements` must outlive this. Nodes `held` keep their rest positions `rest` (3 per node);
  /// `loads` are the full dead nodal forces, N. Starts unloaded, at rest. Throws
  /// std::invalid_argument when a size does not match or a held node does not exist.
  StaticEquilibrium(const HyperelasticElements& elements, const Eigen::VectorXd& rest,
                    const std::vector<int>& held, const Eigen::VectorXd& loads);

  /// Applies the load up to `fraction` of the full load (from the fraction applied so far) in
  /// the settings' increments.
  StaticReport loadTo(double fraction, const StaticSettings& settings = {});

  const Eigen::VectorXd& positions() const { return x_; }
  Eigen::VectorXd displacements() const { return x_ - rest_; }
  double fraction() const { return fraction_; }

 private:
  /// Newton's iterations at the load now; adds to the report.
  void solveAtLoad(const StaticSettings& settings, StaticReport& report);
  /// dPi/dx on the free DOFs (held ones zero); `scale`, if given, becomes the largest nodal
  /// force in play (elastic, reactions included, or applied), N.
  Eigen::VectorXd gradient(const Eigen::VectorXd& x, double* scale = nullptr) const;
  double potential(const Eigen::VectorXd& x) const;
  /// The Newton step for `gradient`; `projected` says which matrix gave it.
  Eigen::VectorXd newtonStep(const Eigen::VectorXd& gradient, bool& projected) const;

  const HyperelasticElements& elements_;
  Eigen::VectorXd rest_, loads_, x_;
  std::vector<int> free_;  ///< per DOF its index among the free ones, -1 when held
  int free_count_ = 0;
  double fraction_ = 0.0;
};

}  // namespace deformable_sim::core
