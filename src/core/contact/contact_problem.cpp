#include "deformable_sim/core/contact/contact_problem.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cassert>
#include <cmath>

namespace deformable_sim::core {

namespace {

/// The larger eigenvalue of the symmetric part of a 2x2 block.
double largerEigenvalue(const Eigen::Matrix2d& m) {
  const double mean = 0.5 * (m(0, 0) + m(1, 1));
  const double half_difference = 0.5 * (m(0, 0) - m(1, 1));
  const double off = 0.5 * (m(0, 1) + m(1, 0));
  return mean + std::hypot(half_difference, off);
}

/// `t` if it lies in the disc of `radius`, else its nearest point on the rim.
Eigen::Vector2d intoDisc(const Eigen::Vector2d& t, double radius) {
  const double length = t.norm();
  if (length <= radius) return t;
  return radius > 0.0 ? Eigen::Vector2d(radius / length * t) : Eigen::Vector2d::Zero();
}

}  // namespace

Eigen::Matrix3d contactFrameFor(const Eigen::Vector3d& normal) {
  // The first tangent across the world axis least along the normal: never near parallel to it.
  int least = 0;
  normal.cwiseAbs().minCoeff(&least);
  const Eigen::Vector3d first = normal.cross(Eigen::Vector3d::Unit(least)).normalized();
  Eigen::Matrix3d frame;
  frame << normal, first, normal.cross(first);
  return frame;
}

void ContactProblem::reserve(int max_contacts, int max_couplings) {
  frames_.reserve(max_contacts);
  friction_.reserve(max_contacts);
  free_velocities_.reserve(max_contacts);
  targets_.reserve(max_contacts);
  diagonal_.reserve(max_contacts);
  tangent_steps_.reserve(max_contacts);
  impulses_.reserve(max_contacts);
  velocities_.reserve(max_contacts);
  fill_.reserve(max_contacts);
  next_.reserve(max_contacts);
  slopes_.reserve(max_contacts);
  slot_.reserve(max_contacts);
  step_.reserve(max_contacts);
  before_step_.reserve(max_contacts);
  newton_space_.get();
  row_start_.reserve(max_contacts + 1);
  couplings_.reserve(max_couplings);
  row_cols_.reserve(2 * static_cast<size_t>(max_couplings));
  row_blocks_.reserve(2 * static_cast<size_t>(max_couplings));
}

void ContactProblem::begin(int count) {
  // assign() and clear() within the reserve allocate nothing.
  frames_.assign(count, Eigen::Matrix3d::Identity());
  friction_.assign(count, 0.0);
  free_velocities_.assign(count, Eigen::Vector3d::Zero());
  targets_.assign(count, 0.0);
  diagonal_.assign(count, Eigen::Matrix3d::Zero());
  tangent_steps_.assign(count, 0.0);
  impulses_.assign(count, Eigen::Vector3d::Zero());
  velocities_.assign(count, Eigen::Vector3d::Zero());
  fill_.assign(count, 0);
  next_.assign(count, Eigen::Vector3d::Zero());
  slopes_.assign(count, {Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()});
  slot_.assign(count, -1);
  step_.assign(count, Eigen::Vector3d::Zero());
  before_step_.assign(count, Eigen::Vector3d::Zero());
  row_start_.assign(count + 1, 0);
  couplings_.clear();
  row_cols_.clear();
  row_blocks_.clear();
}

void ContactProblem::setContact(int i, const Eigen::Matrix3d& frame, double friction,
                                const Eigen::Vector3d& free_velocity,
                                double target_normal_velocity) {
  assert(friction >= 0.0);
  frames_[i] = frame;
  friction_[i] = friction;
  free_velocities_[i] = free_velocity;
  targets_[i] = target_normal_velocity;
  diagonal_[i].setZero();
}

void ContactProblem::addDiagonal(int i, const Eigen::Matrix3d& block) { diagonal_[i] += block; }

void ContactProblem::addCoupling(int i, int j, const Eigen::Matrix3d& ij,
                                 const Eigen::Matrix3d& ji) {
  assert(i != j);
  couplings_.push_back({i, j, ij, ji});
}

Eigen::Matrix3d ContactProblem::inContactFrames(int i, int j,
                                                const Eigen::Matrix3d& world_block) const {
  return frames_[i].transpose() * world_block * frames_[j];
}

void ContactProblem::buildRows() {
  // A counting sort by row: each coupling lands in row i as W_ij and in row j as W_ji, the
  // entries of a row in the order the couplings were added (the same order every time).
  const int n = size();
  std::fill(row_start_.begin(), row_start_.end(), 0);
  for (const Coupling& c : couplings_) {
    ++row_start_[c.row + 1];
    ++row_start_[c.col + 1];
  }
  for (int i = 0; i < n; ++i) row_start_[i + 1] += row_start_[i];
  row_cols_.resize(row_start_[n]);
  row_blocks_.resize(row_start_[n]);
  std::fill(fill_.begin(), fill_.end(), 0);
  for (const Coupling& c : couplings_) {
    const int in_row = row_start_[c.row] + fill_[c.row]++;
    row_cols_[in_row] = c.col;
    row_blocks_[in_row] = c.block;
    const int in_col = row_start_[c.col] + fill_[c.col]++;
    row_cols_[in_col] = c.row;
    row_blocks_[in_col] = c.back;
  }
}

Eigen::Vector3d ContactProblem::velocityOf(int i) const {
  Eigen::Vector3d v = free_velocities_[i] + diagonal_[i] * impulses_[i];
  for (int k = row_start_[i]; k < row_start_[i + 1]; ++k) {
    v.noalias() += row_blocks_[k] * impulses_[row_cols_[k]];
  }
  return v;
}

void ContactProblem::projectIntoCone(int i) {
  Eigen::Vector3d& impulse = impulses_[i];
  if (!(diagonal_[i](0, 0) > 0.0)) {
    impulse.setZero();
    return;
  }
  impulse[0] = std::max(0.0, impulse[0]);
  impulse.tail<2>() = intoDisc(impulse.tail<2>(), friction_[i] * impulse[0]);
}

Eigen::Vector3d ContactProblem::updated(int i, const Eigen::Vector3d& impulse,
                                        const Eigen::Vector3d& v,
                                        std::pair<Eigen::Matrix3d, Eigen::Matrix3d>* slopes) const {
  const Eigen::Matrix3d& w = diagonal_[i];
  if (slopes) {
    slopes->first.setZero();
    slopes->second.setZero();
  }
  Eigen::Vector3d next = Eigen::Vector3d::Zero();
  // The normal first: the min-map of Signorini's complementarity, one scalar step.
  const double pushed = impulse[0] - (v[0] - targets_[i]) / w(0, 0);
  if (!(pushed > 0.0)) return next;  // no push, no friction: every slope zero
  next[0] = pushed;
  // Then friction, with the slip the new normal impulse leaves (W_tn couples them).
  const Eigen::Vector2d slip = v.tail<2>() + w.block<2, 1>(1, 0) * (next[0] - impulse[0]);
  const double step = tangent_steps_[i];
  const Eigen::Vector2d wanted =
      step > 0.0 ? Eigen::Vector2d(impulse.tail<2>() - slip / step) : Eigen::Vector2d::Zero();
  const double radius = friction_[i] * next[0], length = wanted.norm();
  next.tail<2>() = intoDisc(wanted, radius);
  if (!slopes) return next;
  // The normal's slopes, then the wanted friction's, then through the disc's projection.
  Eigen::Matrix3d& by_impulse = slopes->first;
  Eigen::Matrix3d& by_velocity = slopes->second;
  by_impulse(0, 0) = 1.0;
  by_velocity(0, 0) = -1.0 / w(0, 0);
  if (!(step > 0.0) || !(radius > 0.0)) return next;
  Eigen::Matrix<double, 2, 3> wanted_by_velocity;
  wanted_by_velocity << w.block<2, 1>(1, 0) / (w(0, 0) * step), -Eigen::Matrix2d::Identity() / step;
  if (length <= radius) {
    by_impulse.bottomRightCorner<2, 2>().setIdentity();
    by_velocity.bottomRows<2>() = wanted_by_velocity;
    return next;
  }
  // On the rim: t = radius u with u = wanted / |wanted|, so dt = radius / |wanted| (I - u u^T)
  // d wanted + μ u d(normal).
  const Eigen::Vector2d u = wanted / length;
  const Eigen::Matrix2d across =
      radius / length * (Eigen::Matrix2d::Identity() - u * u.transpose());
  by_impulse.bottomRows<2>() = friction_[i] * u * by_impulse.row(0);
  by_impulse.bottomRightCorner<2, 2>() += across;
  by_velocity.bottomRows<2>() = across * wanted_by_velocity + friction_[i] * u * by_velocity.row(0);
  return next;
}

double ContactProblem::update(int i) {
  if (!(diagonal_[i](0, 0) > 0.0)) return 0.0;  // nothing can move it: it keeps zero
  Eigen::Vector3d& impulse = impulses_[i];
  const Eigen::Vector3d next = updated(i, impulse, velocityOf(i));
  const double change = (diagonal_[i] * (next - impulse)).norm();
  impulse = next;
  return change;
}

double ContactProblem::residual() {
  double largest = 0.0;
  for (int i = 0; i < size(); ++i) {
    velocities_[i] = velocityOf(i);
    if (!(diagonal_[i](0, 0) > 0.0)) continue;
    const Eigen::Vector3d next = updated(i, impulses_[i], velocities_[i]);
    largest = std::max(largest, (diagonal_[i] * (next - impulses_[i])).norm());
  }
  return largest;
}

ContactSolveReport ContactProblem::solve(const ContactSolveSettings& settings) {
  assert(settings.max_sweeps >= 1);
  buildRows();
  for (int i = 0; i < size(); ++i) {
    tangent_steps_[i] = largerEigenvalue(diagonal_[i].bottomRightCorner<2, 2>());
    projectIntoCone(i);
  }
  ContactSolveReport report;
  for (int sweep = 1; sweep <= settings.max_sweeps; ++sweep) {
    double change = 0.0;
    for (int i = 0; i < size(); ++i) change = std::max(change, update(i));
    report.sweeps = sweep;
    // Newton's answer, when it has one, is checked as the sweeps' would be.
    if (sweep % settings.sweeps_before_newton == 0 && newton(settings, report)) change = 0.0;
    // The updates' changes are cheap to watch; the residual, a pass of its own, is taken only
    // when they say the sweeps are done (later updates may have disturbed earlier contacts).
    if (change > settings.tolerance) continue;
    report.residual = residual();
    if (report.residual <= settings.tolerance) {
      report.converged = true;
      return report;
    }
  }
  report.residual = residual();
  report.converged = report.residual <= settings.tolerance;
  return report;
}

}  // namespace deformable_sim::core
