#include "deformable_sim/core/elements/material.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace deformable_sim::core {

namespace {
[[noreturn]] void reject(const char* what, double value, const char* range) {
  std::ostringstream message;
  message << "material: " << what << " is " << value << ", it must be " << range;
  throw std::invalid_argument(message.str());
}
}  // namespace

void validate(const LinearElasticMaterial& m) {
  if (!(m.youngs_modulus > 0.0) || !std::isfinite(m.youngs_modulus)) {
    reject("youngs_modulus", m.youngs_modulus, "finite and > 0 Pa");
  }
  if (!(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5)) {
    reject("poisson_ratio", m.poisson_ratio, "in (-1, 0.5)");
  }
  if (!(m.density > 0.0) || !std::isfinite(m.density)) {
    reject("density", m.density, "finite and > 0 kg/m^3");
  }
}

double lameLambda(const LinearElasticMaterial& m) {
  return m.youngs_modulus * m.poisson_ratio /
         ((1.0 + m.poisson_ratio) * (1.0 - 2.0 * m.poisson_ratio));
}

double lameMu(const LinearElasticMaterial& m) {
  return m.youngs_modulus / (2.0 * (1.0 + m.poisson_ratio));
}

Eigen::Matrix<double, 6, 6> elasticityMatrix(const LinearElasticMaterial& m) {
  const double lambda = lameLambda(m);
  const double mu = lameMu(m);
  Eigen::Matrix<double, 6, 6> d = Eigen::Matrix<double, 6, 6>::Zero();
  d.topLeftCorner<3, 3>().setConstant(lambda);
  d.topLeftCorner<3, 3>().diagonal().array() += 2.0 * mu;
  d.bottomRightCorner<3, 3>().diagonal().setConstant(mu);
  return d;
}

}  // namespace deformable_sim::core
