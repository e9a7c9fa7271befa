#include "deformable_sim/core/materials/static_equilibrium.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace deformable_sim::core {

namespace {

/// Halvings of a Newton step before it is taken as it is.
constexpr int kMaxHalvings = 30;
/// Armijo's fraction of the decrease the step's slope promises.
constexpr double kSufficientDecrease = 1e-4;

}  // namespace

StaticEquilibrium::StaticEquilibrium(const HyperelasticElements& elements,
                                     const Eigen::VectorXd& rest, const std::vector<int>& held,
                                     const Eigen::VectorXd& loads)
    : elements_(elements), rest_(rest), loads_(loads), x_(rest) {
  const int dofs = 3 * elements.numNodes();
  if (rest.size() != dofs || loads.size() != dofs) {
    std::ostringstream message;
    message << "static equilibrium: " << elements.numNodes() << " nodes need " << dofs
            << " positions and loads, got " << rest.size() << " and " << loads.size();
    throw std::invalid_argument(message.str());
  }
  free_.assign(dofs, 0);
  for (int node : held) {
    if (node < 0 || node >= elements.numNodes()) {
      throw std::invalid_argument("static equilibrium: held node " + std::to_string(node) +
                                  " does not exist");
    }
    for (int k = 0; k < 3; ++k) free_[3 * node + k] = -1;
  }
  for (int& index : free_) {
    if (index == 0) index = free_count_++;
  }
}

Eigen::VectorXd StaticEquilibrium::gradient(const Eigen::VectorXd& x, double* scale) const {
  Eigen::VectorXd g = -fraction_ * loads_;
  Eigen::VectorXd forces = Eigen::VectorXd::Zero(x.size());
  elements_.addForces(x, forces);
  g -= forces;
  // The largest nodal force in play, the supports' reactions among them: what round-off in the
  // residual is measured against.
  if (scale) {
    *scale = std::max(
        {forces.lpNorm<Eigen::Infinity>(), fraction_ * loads_.lpNorm<Eigen::Infinity>(), 1e-300});
  }
  for (int i = 0; i < g.size(); ++i) {
    if (free_[i] < 0) g[i] = 0.0;
  }
  return g;
}

double StaticEquilibrium::potential(const Eigen::VectorXd& x) const {
  return elements_.energy(x) - fraction_ * loads_.dot(x - rest_);
}

Eigen::VectorXd StaticEquilibrium::newtonStep(const Eigen::VectorXd& gradient,
                                              bool& projected) const {
  Eigen::VectorXd right(free_count_);
  for (int i = 0; i < gradient.size(); ++i) {
    if (free_[i] >= 0) right[free_[i]] = -gradient[i];
  }
  for (const bool project : {false, true}) {
    const Eigen::SparseMatrix<double> full = elements_.tangent(x_, project);
    std::vector<Eigen::Triplet<double>> entries;
    for (int c = 0; c < full.outerSize(); ++c) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(full, c); it; ++it) {
        if (free_[it.row()] >= 0 && free_[it.col()] >= 0)
          entries.emplace_back(free_[it.row()], free_[it.col()], it.value());
      }
    }
    Eigen::SparseMatrix<double> matrix(free_count_, free_count_);
    matrix.setFromTriplets(entries.begin(), entries.end());
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(matrix);
    // The exact tangent only where it is positive definite: its step then goes downhill.
    if (ldlt.info() != Eigen::Success || (ldlt.vectorD().array() <= 0.0).any()) continue;
    const Eigen::VectorXd solved = ldlt.solve(right);
    Eigen::VectorXd step = Eigen::VectorXd::Zero(gradient.size());
    for (int i = 0; i < gradient.size(); ++i) {
      if (free_[i] >= 0) step[i] = solved[free_[i]];
    }
    projected = project;
    return step;
  }
  projected = true;
  return -gradient;  // no positive definite matrix (every free node loose): steepest descent
}

void StaticEquilibrium::solveAtLoad(const StaticSettings& settings, StaticReport& report) {
  double scale = 0.0;
  Eigen::VectorXd g = gradient(x_, &scale);
  for (int iteration = 0; iteration < settings.max_iterations; ++iteration) {
    if (g.lpNorm<Eigen::Infinity>() <= settings.tolerance * scale) return;
    bool projected = false;
    const Eigen::VectorXd step = newtonStep(g, projected);
    ++report.iterations;
    report.projected += projected;
    // Backtracking on Pi; near the answer Pi's changes drown in round-off, and a step that
    // lowers the residual is taken instead.
    const double before = potential(x_), slope = g.dot(step), residual = g.norm();
    double length = 1.0;
    Eigen::VectorXd x = x_ + step;
    Eigen::VectorXd next = gradient(x);
    for (int halving = 0; halving < kMaxHalvings; ++halving) {
      const double after = potential(x);
      if (after <= before + kSufficientDecrease * length * slope || next.norm() < residual) break;
      length *= 0.5;
      x = x_ + length * step;
      next = gradient(x);
    }
    x_ = x;
    g = gradient(x_, &scale);
  }
}

StaticReport StaticEquilibrium::loadTo(double fraction, const StaticSettings& settings) {
  StaticReport report;
  report.converged = true;
  const double from = fraction_;
  for (int k = 1; k <= settings.increments; ++k) {
    fraction_ = from + (fraction - from) * k / settings.increments;
    solveAtLoad(settings, report);
    double scale = 0.0;
    const double residual = gradient(x_, &scale).lpNorm<Eigen::Infinity>();
    report.residual = residual;
    report.converged = report.converged && residual <= settings.tolerance * scale;
  }
  return report;
}

}  // namespace deformable_sim::core
