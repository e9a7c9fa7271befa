// ContactProblem's semismooth Newton method (see contact_problem.h). The equations are
// F(λ) = λ - U(λ) = 0, with U each contact's update from its velocity v = W λ + v_free. Per
// contact, U_i's slopes are A_i by its own impulse and B_i by its velocity, so F's Jacobian has
// rows (I - A_i) E_i - B_i W_i. (E_i picks contact i, W_i its row of W.) A contact that does not
// push has A_i = B_i = 0: its step is plain, Δ_i = U_i - λ_i, and only the pushing contacts are
// left to solve for, densely.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "deformable_sim/core/contact/contact_problem.h"

namespace deformable_sim::core {

namespace {
/// Halvings of a step before it is given up.
constexpr int kMaxHalvings = 10;
/// Newton stops within this fraction of the tolerance.
constexpr double kNewtonAim = 0.1;
/// Armijo's fraction: a step of length α must lower the squared error by at least this times α.
constexpr double kSufficientDecrease = 1e-4;

/// Solves a x = b for the leading n rows and columns, by Gaussian elimination with partial
/// pivoting, in place: a is overwritten, b becomes x. False when a pivot is zero or not finite.
/// Written out because Eigen's PartialPivLU goes blocked past 16 rows and its product, run in
/// parallel by OpenMP, allocates its work space at every call: a solve of the step must not.
bool solveInPlace(Eigen::MatrixXd& a, Eigen::VectorXd& b, int n) {
  for (int k = 0; k < n; ++k) {
    int pivot = k;
    a.col(k).segment(k, n - k).cwiseAbs().maxCoeff(&pivot);
    pivot += k;
    if (!(std::abs(a(pivot, k)) > 0.0) || !std::isfinite(a(pivot, k))) return false;
    if (pivot != k) {
      a.row(k).head(n).swap(a.row(pivot).head(n));
      std::swap(b[k], b[pivot]);
    }
    for (int i = k + 1; i < n; ++i) {
      const double factor = a(i, k) / a(k, k);
      if (factor == 0.0) continue;
      a.row(i).segment(k + 1, n - k - 1) -= factor * a.row(k).segment(k + 1, n - k - 1);
      b[i] -= factor * b[k];
    }
  }
  for (int k = n - 1; k >= 0; --k) {
    b[k] = (b[k] - a.row(k).segment(k + 1, n - k - 1).dot(b.segment(k + 1, n - k - 1))) / a(k, k);
  }
  return true;
}
}  // namespace

struct ContactProblem::NewtonSystem {
  /// A dense system of a fixed size, allocated once, of which the pushing contacts' rows and
  /// columns are solved. Sizes double from one to the next.
  struct Sized {
    explicit Sized(int rows) : jacobian(rows, rows), right(rows) {}
    Eigen::MatrixXd jacobian;
    Eigen::VectorXd right;  ///< and, solved, the step
  };
  NewtonSystem() {
    for (int contacts = 8; contacts <= kMaxNewtonContacts; contacts *= 2)
      sizes.emplace_back(3 * contacts);
  }
  /// The smallest that holds `rows`.
  Sized& holding(int rows) {
    for (Sized& s : sizes) {
      if (s.right.size() >= rows) return s;
    }
    return sizes.back();
  }
  std::vector<Sized> sizes;
};

ContactProblem::NewtonSpace::NewtonSpace() = default;
ContactProblem::NewtonSpace::NewtonSpace(const NewtonSpace& other)
    : system_(other.system_ ? std::make_unique<NewtonSystem>() : nullptr) {}
ContactProblem::NewtonSpace& ContactProblem::NewtonSpace::operator=(const NewtonSpace& other) {
  if (other.system_ && !system_) system_ = std::make_unique<NewtonSystem>();
  return *this;
}
ContactProblem::NewtonSpace::NewtonSpace(NewtonSpace&& other) noexcept = default;
ContactProblem::NewtonSpace& ContactProblem::NewtonSpace::operator=(NewtonSpace&& other) noexcept =
    default;
ContactProblem::NewtonSpace::~NewtonSpace() = default;

ContactProblem::NewtonSystem& ContactProblem::NewtonSpace::get() {
  if (!system_) system_ = std::make_unique<NewtonSystem>();
  return *system_;
}

std::pair<double, double> ContactProblem::linearize() {
  double squares = 0.0, largest = 0.0;
  for (int i = 0; i < size(); ++i) {
    velocities_[i] = velocityOf(i);
    if (!(diagonal_[i](0, 0) > 0.0)) {  // nothing can move it: it stays as it is
      next_[i] = impulses_[i];
      slopes_[i].first.setZero();
      slopes_[i].second.setZero();
      continue;
    }
    next_[i] = updated(i, impulses_[i], velocities_[i], &slopes_[i]);
    const double error = (diagonal_[i] * (next_[i] - impulses_[i])).norm();
    squares += error * error;
    largest = std::max(largest, error);
  }
  return {squares, largest};
}

bool ContactProblem::newtonStep() {
  // Number the pushing contacts; the others' steps are known.
  int pushing = 0;
  for (int i = 0; i < size(); ++i) {
    const bool pushes = slopes_[i].first(0, 0) > 0.0;
    slot_[i] = pushes ? pushing++ : -1;
    step_[i] = next_[i] - impulses_[i];
  }
  if (pushing > kMaxNewtonContacts) return false;
  if (pushing == 0) return true;
  const int rows = 3 * pushing;
  NewtonSystem::Sized& system = newton_space_.get().holding(rows);
  system.jacobian.topLeftCorner(rows, rows).setZero();
  system.right.head(rows).setZero();
  for (int i = 0; i < size(); ++i) {
    const int s = slot_[i];
    if (s < 0) continue;
    const Eigen::Matrix3d &a = slopes_[i].first, &b = slopes_[i].second;
    system.jacobian.block<3, 3>(3 * s, 3 * s) = Eigen::Matrix3d::Identity() - a - b * diagonal_[i];
    Eigen::Vector3d right = step_[i];  // -F_i
    for (int k = row_start_[i]; k < row_start_[i + 1]; ++k) {
      const int j = row_cols_[k];
      if (slot_[j] >= 0) {
        system.jacobian.block<3, 3>(3 * s, 3 * slot_[j]) -= b * row_blocks_[k];
      } else {
        right.noalias() += b * (row_blocks_[k] * step_[j]);
      }
    }
    system.right.segment<3>(3 * s) = right;
  }
  if (!solveInPlace(system.jacobian, system.right, rows) || !system.right.head(rows).allFinite()) {
    return false;
  }
  for (int i = 0; i < size(); ++i) {
    if (slot_[i] >= 0) step_[i] = system.right.segment<3>(3 * slot_[i]);
  }
  return true;
}

void ContactProblem::takeUpdates() {
  linearize();
  for (int i = 0; i < size(); ++i) impulses_[i] = next_[i];
}

bool ContactProblem::newton(const ContactSolveSettings& settings, ContactSolveReport& report) {
  double squares = linearize().first;
  bool converged = false;
  for (int k = 0; k < settings.max_newton_steps; ++k) {
    if (!newtonStep()) break;
    ++report.newton_steps;
    // Backtracking: the longest of 1, 1/2, 1/4, ... that lowers the squared error enough.
    before_step_ = impulses_;
    bool lowered = false;
    double length = 1.0;
    for (int halving = 0; halving <= kMaxHalvings && !lowered; ++halving, length *= 0.5) {
      for (int i = 0; i < size(); ++i) impulses_[i] = before_step_[i] + length * step_[i];
      const auto [now, largest] = linearize();
      lowered = now <= (1.0 - kSufficientDecrease * length) * squares;
      if (lowered) {
        squares = now;
        // With room for the last updates, which may move it a little.
        converged = largest <= kNewtonAim * settings.tolerance;
      }
    }
    if (!lowered) {
      impulses_ = before_step_;
      break;
    }
    if (converged) break;
  }
  takeUpdates();
  return converged;
}

}  // namespace deformable_sim::core
