#include "deformable_sim/core/bodies/implicit_response.h"

namespace deformable_sim::core {

void ImplicitResponse::begin(FiniteElementBody& body) {
  body_ = &body;
  for (int i : used_) slot_of_[i] = -1;
  used_.clear();
  slots_ = 0;
  solves_ = 0;
}

int ImplicitResponse::slot(int i) {
  if (slot_of_[i] >= 0) return slot_of_[i];
  const int s = slots_++;
  slot_of_[i] = s;
  used_.push_back(i);
  const Eigen::Index size = 3 * body_->numNodes();
  while (static_cast<int>(columns_.size()) < 3 * slots_) columns_.emplace_back(size);
  for (int d = 0; d < 3; ++d) {
    Eigen::VectorXd& column = columns_[3 * s + d];
    if (body_->isConstrained(i)) {  // held: it passes every impulse to what holds it
      column.setZero();
      continue;
    }
    if (unit_.size() != size) unit_ = Eigen::VectorXd::Zero(size);
    unit_[3 * i + d] = 1.0;
    body_->solveLastStep(unit_, column);
    unit_[3 * i + d] = 0.0;
    ++solves_;
  }
  return s;
}

Eigen::Matrix3d ImplicitResponse::block(int j, int i) {
  const int s = slot(i);
  Eigen::Matrix3d b;
  for (int d = 0; d < 3; ++d) b.col(d) = columns_[3 * s + d].segment<3>(3 * j);
  return b;
}

void ImplicitResponse::add(int i, const Eigen::Vector3d& impulse, Eigen::VectorXd& dv) {
  const int s = slot(i);
  for (int d = 0; d < 3; ++d) {
    if (impulse[d] != 0.0) dv += impulse[d] * columns_[3 * s + d];
  }
}

}  // namespace deformable_sim::core
