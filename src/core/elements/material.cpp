#include "deformable_sim/core/elements/material.h"

#include "deformable_sim/core/elements/parameter_limits.h"

namespace deformable_sim::core {

void validate(const LinearElasticMaterial& m) {
  checkParameter(Parameter::kYoungsModulus, m.youngs_modulus, "material: ");
  checkParameter(Parameter::kPoissonRatio, m.poisson_ratio, "material: ");
  checkParameter(Parameter::kDensity, m.density, "material: ");
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
