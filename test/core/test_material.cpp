#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "deformable_sim/core/elements/material.h"

namespace dc = deformable_sim::core;

namespace {

std::string rejection(const dc::LinearElasticMaterial& m) {
  try {
    dc::validate(m);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Material, AcceptsOrdinaryValues) { EXPECT_NO_THROW(dc::validate({1e6, 0.3, 1000.0})); }

TEST(Material, RejectsImpossibleValuesNamingThem) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(rejection({0.0, 0.3, 1000.0}).find("youngs_modulus is 0"), std::string::npos);
  EXPECT_NE(rejection({-5.0, 0.3, 1000.0}).find("youngs_modulus"), std::string::npos);
  EXPECT_NE(rejection({nan, 0.3, 1000.0}).find("youngs_modulus is nan"), std::string::npos);
  EXPECT_NE(rejection({1e6, 0.5, 1000.0}).find("poisson_ratio is 0.5, it must be in (-1, 0.5)"),
            std::string::npos);
  EXPECT_NE(rejection({1e6, -1.0, 1000.0}).find("poisson_ratio"), std::string::npos);
  EXPECT_NE(rejection({1e6, nan, 1000.0}).find("poisson_ratio is nan"), std::string::npos);
  EXPECT_NE(rejection({1e6, 0.3, 0.0}).find("density is 0"), std::string::npos);
  EXPECT_NE(rejection({1e6, 0.3, INFINITY}).find("density is inf"), std::string::npos);
}

TEST(Material, LameParametersAndElasticityMatrix) {
  const dc::LinearElasticMaterial m{1e6, 0.3, 1000.0};
  EXPECT_NEAR(dc::lameMu(m), 1e6 / 2.6, 1e-6);
  EXPECT_NEAR(dc::lameLambda(m), 1e6 * 0.3 / (1.3 * 0.4), 1e-6);
  // Uniaxial stress: with strain (1, -nu, -nu, 0, 0, 0) the stress is (E, 0, 0, 0, 0, 0).
  Eigen::Matrix<double, 6, 1> strain;
  strain << 1.0, -0.3, -0.3, 0.0, 0.0, 0.0;
  const Eigen::Matrix<double, 6, 1> stress = dc::elasticityMatrix(m) * strain;
  EXPECT_NEAR(stress[0], 1e6, 1e-6);
  EXPECT_NEAR(stress.tail<5>().norm(), 0.0, 1e-6);
  // Pure shear: engineering strain gamma gives stress mu * gamma.
  strain.setZero();
  strain[3] = 1.0;
  EXPECT_NEAR((dc::elasticityMatrix(m) * strain)[3], dc::lameMu(m), 1e-6);
}
