#include "deformable_sim/core/bodies/implicit_response.h"

#include <algorithm>
#include <cmath>

namespace deformable_sim::core {

namespace {

/// A plane's normal may swing by this little (its cosine) and still give the same spring.
constexpr double kSamePlane = 0.9999;

}  // namespace

ImplicitResponse::ImplicitResponse(const FiniteElementBody& body)
    : slot_of_(body.numNodes(), -1),
      held_(body.numNodes(), 0),
      turns_(body.elasticity().rotations().size()) {
  planes_.reserve(body.numNodes());
}

void ImplicitResponse::begin(FiniteElementBody& body) {
  body_ = &body;
  solves_ = 0;
  if (stillAnswers(body)) return;
  forget();
  remember(body);
}

void ImplicitResponse::forget() {
  for (int i : used_) slot_of_[i] = -1;
  used_.clear();
  slots_ = 0;
  for (int id : corner_ids_) corner_of_id_[id] = -1;
  corner_ids_.clear();
  corners_kept_ = 0;
  has_impulses_ = false;
}

bool ImplicitResponse::stillAnswers(const FiniteElementBody& body) const {
  if (!remembered_ || body.matrixVersion() != matrix_version_) return false;
  for (int i = 0; i < body.numNodes(); ++i) {
    if (held_[i] != static_cast<char>(body.isConstrained(i))) return false;
  }
  const std::vector<PlaneHold>& planes = body.planeHolds();
  if (planes.size() != planes_.size()) return false;
  for (size_t k = 0; k < planes.size(); ++k) {
    if (planes[k].node != planes_[k].node ||
        !(planes[k].normal.dot(planes_[k].normal) >= kSamePlane)) {
      return false;
    }
  }
  const std::vector<Eigen::Matrix3d>& rotations = body.elasticity().rotations();
  if (rotations.size() != turns_.size()) return false;
  double squared = 0.0;
  for (size_t e = 0; e < rotations.size(); ++e) {
    // The angle of R_then^T R_now from its trace.
    const double c = 0.5 * ((turns_[e].transpose() * rotations[e]).trace() - 1.0);
    const double angle = std::acos(std::clamp(c, -1.0, 1.0));
    squared += angle * angle;
  }
  return rotations.empty() || std::sqrt(squared / rotations.size()) < kStaleTurn;
}

void ImplicitResponse::remember(const FiniteElementBody& body) {
  remembered_ = true;
  matrix_version_ = body.matrixVersion();
  for (int i = 0; i < body.numNodes(); ++i) held_[i] = static_cast<char>(body.isConstrained(i));
  planes_.assign(body.planeHolds().begin(), body.planeHolds().end());  // within the reserve
  const std::vector<Eigen::Matrix3d>& rotations = body.elasticity().rotations();
  std::copy(rotations.begin(), rotations.end(), turns_.begin());
}

void ImplicitResponse::makeRoom(int slots) {
  if (slots <= capacity_) return;
  const int capacity = std::max({slots, 2 * capacity_, 16});
  Eigen::MatrixXd near = Eigen::MatrixXd::Zero(3 * capacity, 3 * capacity);
  near.topLeftCorner(3 * capacity_, 3 * capacity_) = near_;
  near_.swap(near);
  Eigen::VectorXd impulses = Eigen::VectorXd::Zero(3 * capacity);
  Eigen::VectorXd changes = Eigen::VectorXd::Zero(3 * capacity);
  impulses.head(3 * capacity_) = impulses_;
  changes.head(3 * capacity_) = near_changes_;
  impulses_.swap(impulses);
  near_changes_.swap(changes);
  capacity_ = capacity;
}

int ImplicitResponse::slot(int i) {
  if (slot_of_[i] >= 0) return slot_of_[i];
  const int s = slots_++;
  makeRoom(slots_);
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
  // Its rows and columns in the dense block; its node's change from the impulses so far.
  for (int t = 0; t <= s; ++t) {
    for (int d = 0; d < 3; ++d) {
      near_.block<3, 1>(3 * t, 3 * s + d) = columns_[3 * s + d].segment<3>(3 * used_[t]);
      near_.block<3, 1>(3 * s, 3 * t + d) = columns_[3 * t + d].segment<3>(3 * i);
    }
  }
  impulses_.segment<3>(3 * s).setZero();
  near_changes_.segment<3>(3 * s) =
      near_.middleRows(3 * s, 3).leftCols(3 * s) * impulses_.head(3 * s);
  return s;
}

Eigen::Matrix3d ImplicitResponse::block(int j, int i) {
  const int s = slot(i);
  Eigen::Matrix3d b;
  for (int d = 0; d < 3; ++d) b.col(d) = columns_[3 * s + d].segment<3>(3 * j);
  return b;
}

int ImplicitResponse::newPoint() {
  const int p = kept_points_++;
  if (points_.rows() < 3 * capacity_ || points_.cols() < 3 * kept_points_) {
    // Grows, keeping the points summed so far, only past the most ever kept.
    const Eigen::Index cols = std::max<Eigen::Index>(3 * kept_points_, 2 * points_.cols());
    points_.conservativeResize(3 * capacity_, cols);
    point_slots_.resize(cols / 3);
  }
  point_slots_[p] = slots_;
  return p;
}

void ImplicitResponse::sumColumns(Eigen::MatrixXd& into, int point, const int* nodes,
                                  const double* weights, int count) const {
  // The first term assigned, not added to zeros: a pass over the sum less.
  auto sum = into.block(0, 3 * point, 3 * slots_, 3);
  const auto column = [&](int k) { return near_.block(0, 3 * slot_of_[nodes[k]], 3 * slots_, 3); };
  if (count == 0) sum.setZero();
  if (count > 0) sum.noalias() = weights[0] * column(0);
  for (int k = 1; k < count; ++k) sum.noalias() += weights[k] * column(k);
}

int ImplicitResponse::keepPoint(const int* nodes, const double* weights, int count) {
  for (int k = 0; k < count; ++k) slot(nodes[k]);  // every slot first: the sum covers them all
  const int p = newPoint();
  sumColumns(points_, p, nodes, weights, count);
  return p;
}

int ImplicitResponse::keepCorner(int id, const int* nodes, const double* weights, int count) {
  for (int k = 0; k < count; ++k) slot(nodes[k]);
  if (id >= static_cast<int>(corner_of_id_.size())) corner_of_id_.resize(id + 1, -1);  // once
  int& c = corner_of_id_[id];
  if (c >= 0 && corner_slots_[c] == slots_) return kCornerHandle + c;  // summed, still good
  if (c < 0) {
    c = corners_kept_++;
    corner_ids_.push_back(id);
    corner_slots_.resize(std::max<size_t>(corner_slots_.size(), corners_kept_));
  }
  if (corner_sums_.rows() < 3 * capacity_ || corner_sums_.cols() < 3 * corners_kept_) {
    const Eigen::Index cols = std::max<Eigen::Index>(3 * corners_kept_, 2 * corner_sums_.cols());
    corner_sums_.conservativeResize(3 * capacity_, cols);
  }
  sumColumns(corner_sums_, c, nodes, weights, count);
  corner_slots_[c] = slots_;
  return kCornerHandle + c;
}

int ImplicitResponse::keepSum(const int* points, const double* weights, int count) {
  for (int k = 0; k < count; ++k) {
    if (pointSlots(points[k]) != slots_) return -1;
  }
  const int p = newPoint();
  auto sum = points_.block(0, 3 * p, 3 * slots_, 3);
  if (count == 3) {  // a triangle's point: its corners' sums in one pass
    sum.noalias() = weights[0] * pointBlock(points[0]) + weights[1] * pointBlock(points[1]) +
                    weights[2] * pointBlock(points[2]);
    return p;
  }
  sum.setZero();
  for (int k = 0; k < count; ++k) sum.noalias() += weights[k] * pointBlock(points[k]);
  return p;
}

void ImplicitResponse::addPointImpulse(int point, const int* nodes, const double* weights,
                                       int count, const Eigen::Vector3d& impulse) {
  if (pointSlots(point) != slots_) {  // a node started touching since: node by node
    for (int k = 0; k < count; ++k) addImpulse(nodes[k], weights[k] * impulse);
    return;
  }
  for (int k = 0; k < count; ++k)
    impulses_.segment<3>(3 * slot_of_[nodes[k]]) += weights[k] * impulse;
  near_changes_.head(3 * slots_).noalias() += pointBlock(point) * impulse;
  has_impulses_ = true;
}

bool ImplicitResponse::keptCompliance(int point, const int* nodes, const double* weights, int count,
                                      Eigen::Matrix3d& w) const {
  if (pointSlots(point) != slots_) return false;
  const auto sum = pointBlock(point);
  w.setZero();
  for (int k = 0; k < count; ++k) w += weights[k] * sum.block<3, 3>(3 * slot_of_[nodes[k]], 0);
  return true;
}

void ImplicitResponse::clearImpulses() {
  kept_points_ = 0;
  impulses_.head(3 * slots_).setZero();
  near_changes_.head(3 * slots_).setZero();
  has_impulses_ = false;
}

void ImplicitResponse::addImpulse(int i, const Eigen::Vector3d& impulse) {
  const int s = slot(i);
  impulses_.segment<3>(3 * s) += impulse;
  near_changes_.head(3 * slots_).noalias() += near_.block(0, 3 * s, 3 * slots_, 3) * impulse;
  has_impulses_ = true;
}

Eigen::Vector3d ImplicitResponse::velocityChange(int j) const {
  if (slot_of_[j] >= 0) return near_changes_.segment<3>(3 * slot_of_[j]);
  Eigen::Vector3d change = Eigen::Vector3d::Zero();
  if (!has_impulses_) return change;
  for (int s = 0; s < slots_; ++s) {
    for (int d = 0; d < 3; ++d) {
      change += impulses_[3 * s + d] * columns_[3 * s + d].segment<3>(3 * j);
    }
  }
  return change;
}

void ImplicitResponse::velocityChanges(Eigen::VectorXd& dv) const {
  dv.setZero();
  if (!has_impulses_) return;
  for (int s = 0; s < slots_; ++s) {
    for (int d = 0; d < 3; ++d) {
      if (impulses_[3 * s + d] != 0.0) dv += impulses_[3 * s + d] * columns_[3 * s + d];
    }
  }
}

}  // namespace deformable_sim::core
