#include "deformable_sim/core/bodies/wrench.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <stdexcept>

namespace deformable_sim::core {

void distributeWrench(const std::vector<Eigen::Vector3d>& positions,
                      const std::vector<double>& weights, const Eigen::Vector3d& force,
                      const Eigen::Vector3d& torque, const Eigen::Vector3d& point,
                      std::vector<Eigen::Vector3d>& forces) {
  if (positions.empty() || positions.size() != weights.size()) {
    throw std::invalid_argument("a wrench needs at least one node, with one weight per node");
  }
  double total_weight = 0.0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < positions.size(); ++i) {
    if (!(weights[i] > 0.0)) throw std::invalid_argument("wrench weights must be > 0");
    total_weight += weights[i];
    centroid += weights[i] * positions[i];
  }
  centroid /= total_weight;

  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  double extent = 0.0;
  for (size_t i = 0; i < positions.size(); ++i) {
    const Eigen::Vector3d r = positions[i] - centroid;
    inertia += weights[i] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
    extent = std::max(extent, r.norm());
  }
  const Eigen::Vector3d reduced_torque = torque + (point - centroid).cross(force);

  // Pseudo-inverse of J: directions it cannot turn about (eigenvalue ~ 0) must carry no torque.
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();
  const double scale = inertia.trace();
  if (scale > 0.0) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(inertia);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d axis = eigen.eigenvectors().col(k);
      const double component = axis.dot(reduced_torque);
      if (eigen.eigenvalues()[k] > 1e-12 * scale) {
        omega += (component / eigen.eigenvalues()[k]) * axis;
      } else if (std::abs(component) > 1e-12 * (reduced_torque.norm() + force.norm() * extent)) {
        throw std::invalid_argument(
            "the nodes lie on one line (or are one node): they cannot carry a torque about that "
            "line");
      }
    }
  } else if (reduced_torque.norm() > 0.0) {
    throw std::invalid_argument("a single node cannot carry a torque");
  }

  forces.resize(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) {
    forces[i] = weights[i] * (force / total_weight + omega.cross(positions[i] - centroid));
  }
}

}  // namespace deformable_sim::core
