// Isotropic linear elastic material, validated when it is made.
#pragma once

#include <Eigen/Core>

namespace deformable_sim::core {

/// The law a finite-element body's E and nu go into: the warped stiffness (linear elasticity,
/// warped by the elements' rotations with the warping effect), or Neo-Hookean
/// (core/materials/neo_hookean.h), which gives the same linear law at small strain.
enum class ElasticLaw { kWarpedStiffness, kNeoHookean };

struct LinearElasticMaterial {
  double youngs_modulus = 1.0e6;  ///< E, Pa; must be > 0
  double poisson_ratio = 0.3;     ///< nu, dimensionless; must be in (-1, 0.5)
  double density = 1000.0;        ///< rho, kg/m^3; must be > 0
  ElasticLaw law = ElasticLaw::kWarpedStiffness;
};

/// Throws std::invalid_argument naming the bad value and its admissible range.
/// Comparisons are written so that NaN fails them too.
void validate(const LinearElasticMaterial& material);

/// Lamé's first parameter lambda = E nu / ((1 + nu)(1 - 2 nu)), Pa.
double lameLambda(const LinearElasticMaterial& material);

/// Shear modulus mu = E / (2 (1 + nu)), Pa.
double lameMu(const LinearElasticMaterial& material);

/// The 6x6 isotropic elasticity matrix D in Voigt order (xx, yy, zz, xy, xz, yz) with engineering
/// shear strains, so that stress = D strain.
Eigen::Matrix<double, 6, 6> elasticityMatrix(const LinearElasticMaterial& material);

}  // namespace deformable_sim::core
