#include "deformable_sim/core/solvers/dense_cholesky.h"

#include "deformable_sim/core/base/cpu_features.h"

namespace deformable_sim::core {

namespace {

// L y = b, then L^T x = y, in place in x (n unknowns; lower: L by columns, upper: L^T by
// columns; inverse: 1 / L_jj). Each unknown, once known, is subtracted from the rest, four
// columns at a time: x_i stays in a register through four multiply-adds taken in column order,
// the same arithmetic as one column at a time, with a quarter of the loads and stores. The
// loops over i vectorize. Inlined into each caller below, so that it is compiled for the
// caller's instruction set.
__attribute__((always_inline)) inline void sweeps(int n, const double* lower, const double* upper,
                                                  const double* inverse, double* x) {
  auto column = [n](const double* m, int j) { return m + static_cast<long>(n) * j; };
  int j = 0;
  for (; j + 4 <= n; j += 4) {
    const double *c0 = column(lower, j), *c1 = column(lower, j + 1), *c2 = column(lower, j + 2),
                 *c3 = column(lower, j + 3);
    const double x0 = x[j] *= inverse[j];
    const double x1 = x[j + 1] = (x[j + 1] - c0[j + 1] * x0) * inverse[j + 1];
    const double x2 = x[j + 2] = ((x[j + 2] - c0[j + 2] * x0) - c1[j + 2] * x1) * inverse[j + 2];
    const double x3 = x[j + 3] =
        (((x[j + 3] - c0[j + 3] * x0) - c1[j + 3] * x1) - c2[j + 3] * x2) * inverse[j + 3];
    for (int i = j + 4; i < n; ++i)
      x[i] = (((x[i] - c0[i] * x0) - c1[i] * x1) - c2[i] * x2) - c3[i] * x3;
  }
  for (; j < n; ++j) {
    const double* c = column(lower, j);
    const double xj = x[j] *= inverse[j];
    for (int i = j + 1; i < n; ++i) x[i] -= c[i] * xj;
  }
  j = n - 1;
  for (; j >= 3; j -= 4) {
    const double *c0 = column(upper, j), *c1 = column(upper, j - 1), *c2 = column(upper, j - 2),
                 *c3 = column(upper, j - 3);
    const double x0 = x[j] *= inverse[j];
    const double x1 = x[j - 1] = (x[j - 1] - c0[j - 1] * x0) * inverse[j - 1];
    const double x2 = x[j - 2] = ((x[j - 2] - c0[j - 2] * x0) - c1[j - 2] * x1) * inverse[j - 2];
    const double x3 = x[j - 3] =
        (((x[j - 3] - c0[j - 3] * x0) - c1[j - 3] * x1) - c2[j - 3] * x2) * inverse[j - 3];
    for (int i = 0; i < j - 3; ++i)
      x[i] = (((x[i] - c0[i] * x0) - c1[i] * x1) - c2[i] * x2) - c3[i] * x3;
  }
  for (; j >= 0; --j) {
    const double* c = column(upper, j);
    const double xj = x[j] *= inverse[j];
    for (int i = 0; i < j; ++i) x[i] -= c[i] * xj;
  }
}

void sweepsPortable(int n, const double* lower, const double* upper, const double* inverse,
                    double* x) {
  sweeps(n, lower, upper, inverse, x);
}

#if defined(__x86_64__)
__attribute__((target("avx2,fma"))) void sweepsAvx2(int n, const double* lower, const double* upper,
                                                    const double* inverse, double* x) {
  sweeps(n, lower, upper, inverse, x);
}
#endif

}  // namespace

void DenseCholesky::resize(int size) {
  matrix_.setZero(size, size);
  factor_ = Eigen::LLT<Eigen::MatrixXd>(size);
  upper_.setZero(size, size);
  inverse_diagonal_.setZero(size);
}

bool DenseCholesky::factorize() {
  factor_.compute(matrix_);
  // Eigen refuses a pivot x <= 0, which a NaN passes: ask for > 0, which it does not.
  if (factor_.info() != Eigen::Success || !(factor_.matrixLLT().diagonal().array() > 0.0).all()) {
    return false;
  }
  upper_.triangularView<Eigen::Upper>() = factor_.matrixLLT().transpose();
  inverse_diagonal_ = factor_.matrixLLT().diagonal().cwiseInverse();
  return true;
}

void DenseCholesky::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  x = b;
  const double* lower = factor_.matrixLLT().data();
#if defined(__x86_64__)
  if (hasAvx2Fma()) {
    sweepsAvx2(size(), lower, upper_.data(), inverse_diagonal_.data(), x.data());
    return;
  }
#endif
  sweepsPortable(size(), lower, upper_.data(), inverse_diagonal_.data(), x.data());
}

}  // namespace deformable_sim::core
