// The Neo-Hookean law in CalculiX's form (core/materials/neo_hookean.h), as Drake tests its
// constitutive models: no stress at rest or under rotation, stress the energy's gradient and its
// derivative the stress's (by central differences), that derivative symmetric, the linear law at
// small strain, and finite energy and forces through inversion.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "deformable_sim/core/materials/neo_hookean.h"

namespace dc = deformable_sim::core;

namespace {

const dc::NeoHookean kFoam = dc::NeoHookean::fromYoungPoisson(3.0e4, 0.45);

/// Deformation gradients from a stretch near rest to a crushed and an inverted element.
std::vector<Eigen::Matrix3d> gradients() {
  std::vector<Eigen::Matrix3d> all;
  Eigen::Matrix3d f;
  f << 1.02, 0.05, -0.01, 0.03, 0.97, 0.04, -0.02, 0.01, 1.05;
  all.push_back(f);
  all.push_back(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()) * f * 1.4);
  f << 0.6, 0.2, 0.1, -0.1, 0.5, 0.2, 0.05, -0.2, 0.8;  // compressed hard, J = 0.28
  all.push_back(f);
  all.push_back(Eigen::Vector3d(0.3, 0.4, 0.5).asDiagonal() * f);   // J past kSmallestVolumeRatio
  all.push_back(Eigen::Vector3d(1.0, 0.9, -0.4).asDiagonal() * f);  // inverted
  return all;
}

/// The largest entry's size, for relative bounds.
double scaleOf(const Eigen::MatrixXd& m) { return std::max(m.cwiseAbs().maxCoeff(), 1e-300); }

TEST(NeoHookean, MaterialFromYoungAndPoissonMatchesTheLinearModuli) {
  const double e = 3.0e4, nu = 0.45;
  const double mu = e / (2 * (1 + nu)), bulk = e / (3 * (1 - 2 * nu));
  EXPECT_DOUBLE_EQ(kFoam.c10(), mu / 2);
  EXPECT_DOUBLE_EQ(kFoam.d1(), 2 / bulk);
}

TEST(NeoHookean, ImpossibleMaterialsAreRefusedByName) {
  EXPECT_THROW(dc::NeoHookean::fromYoungPoisson(-1.0, 0.3), std::invalid_argument);
  EXPECT_THROW(dc::NeoHookean::fromYoungPoisson(1e4, 0.5), std::invalid_argument);
  EXPECT_THROW(dc::NeoHookean::fromYoungPoisson(NAN, 0.3), std::invalid_argument);
  try {
    dc::NeoHookean(1e3, 0.0);
    FAIL() << "D1 = 0 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("D1 = 0"), std::string::npos) << e.what();
  }
}

TEST(NeoHookean, NoEnergyOrStressAtRestOrUnderRotation) {
  for (const Eigen::Matrix3d& r :
       {Eigen::Matrix3d(Eigen::Matrix3d::Identity()),
        Eigen::Matrix3d(Eigen::AngleAxisd(2.5, Eigen::Vector3d(1, -1, 2).normalized()))}) {
    EXPECT_NEAR(kFoam.energyDensity(r), 0.0, 1e-10 * kFoam.c10());
    EXPECT_LT(kFoam.firstPiola(r).cwiseAbs().maxCoeff(), 1e-10 * kFoam.c10());
  }
}

TEST(NeoHookean, StressIsTheEnergysGradient) {
  const double h = 1e-6;
  for (const Eigen::Matrix3d& f : gradients()) {
    Eigen::Matrix3d differences;
    for (int i = 0; i < 9; ++i) {
      Eigen::Matrix3d up = f, down = f;
      up.data()[i] += h;
      down.data()[i] -= h;
      differences.data()[i] = (kFoam.energyDensity(up) - kFoam.energyDensity(down)) / (2 * h);
    }
    const Eigen::Matrix3d p = kFoam.firstPiola(f);
    EXPECT_LT((p - differences).cwiseAbs().maxCoeff(), 1e-6 * scaleOf(p)) << f;
  }
}

TEST(NeoHookean, StressDerivativeIsTheStresssGradientAndSymmetric) {
  const double h = 1e-6;
  for (const Eigen::Matrix3d& f : gradients()) {
    Eigen::Matrix<double, 9, 9> differences;
    for (int i = 0; i < 9; ++i) {
      Eigen::Matrix3d up = f, down = f;
      up.data()[i] += h;
      down.data()[i] -= h;
      differences.col(i) = (kFoam.firstPiola(up) - kFoam.firstPiola(down)).reshaped() / (2 * h);
    }
    const Eigen::Matrix<double, 9, 9> a = kFoam.firstPiolaDerivative(f);
    EXPECT_LT((a - differences).cwiseAbs().maxCoeff(), 1e-6 * scaleOf(a)) << f;
    EXPECT_LT((a - a.transpose()).cwiseAbs().maxCoeff(), 1e-12 * scaleOf(a)) << f;
  }
}

// The same E and nu as the linear law: P(I + eps H) / eps = lambda tr(H) I + mu (H + H^T).
TEST(NeoHookean, SmallStrainGivesTheLinearLaw) {
  for (const double nu : {0.0, 0.3, 0.45, 0.499}) {
    const double e = 1.0e6, eps = 1e-8;
    const dc::NeoHookean law = dc::NeoHookean::fromYoungPoisson(e, nu);
    const double mu = e / (2 * (1 + nu)), lambda = e * nu / ((1 + nu) * (1 - 2 * nu));
    Eigen::Matrix3d h;
    h << 0.3, -0.7, 0.2, 0.5, -0.4, 0.9, -0.1, 0.6, 0.8;
    const Eigen::Matrix3d linear =
        lambda * h.trace() * Eigen::Matrix3d::Identity() + mu * (h + h.transpose());
    const Eigen::Matrix3d p = law.firstPiola(Eigen::Matrix3d::Identity() + eps * h) / eps;
    EXPECT_LT((p - linear).cwiseAbs().maxCoeff(), 1e-6 * scaleOf(linear)) << "nu " << nu;
  }
}

// Crushed flat and turned inside out, an element's energy stays finite and grows the further
// it goes, and its stress pushes it back: along F = diag(1, 1, t), dW/dt < 0 for every t <= 0.1.
TEST(NeoHookean, FiniteThroughInversionAndPushingBack) {
  double last = -1.0;
  for (double t = 0.2; t >= -1.0; t -= 0.01) {
    const Eigen::Matrix3d f = Eigen::Vector3d(1.0, 1.0, t).asDiagonal();
    const double w = kFoam.energyDensity(f);
    ASSERT_TRUE(std::isfinite(w)) << t;
    ASSERT_TRUE(kFoam.firstPiola(f).allFinite()) << t;
    ASSERT_TRUE(kFoam.firstPiolaDerivative(f).allFinite()) << t;
    EXPECT_GT(w, last) << t;
    EXPECT_LT(kFoam.firstPiola(f)(2, 2), 0.0) << t;
    last = w;
  }
  EXPECT_TRUE(std::isfinite(kFoam.energyDensity(Eigen::Matrix3d::Zero())));
  EXPECT_TRUE(kFoam.firstPiola(Eigen::Matrix3d::Zero()).allFinite());
}

// Where J^(-2/3) hands over to its continuation, energy, stress and derivative are continuous.
TEST(NeoHookean, ContinuousWhereTheContinuationBegins) {
  const double j = dc::NeoHookean::kSmallestVolumeRatio, d = 1e-9;
  const Eigen::Matrix3d above = Eigen::Vector3d(1.0, 1.0, j + d).asDiagonal();
  const Eigen::Matrix3d below = Eigen::Vector3d(1.0, 1.0, j - d).asDiagonal();
  EXPECT_NEAR(kFoam.energyDensity(above), kFoam.energyDensity(below),
              1e-6 * kFoam.energyDensity(above));
  EXPECT_LT((kFoam.firstPiola(above) - kFoam.firstPiola(below)).cwiseAbs().maxCoeff(),
            1e-6 * scaleOf(kFoam.firstPiola(above)));
  EXPECT_LT(
      (kFoam.firstPiolaDerivative(above) - kFoam.firstPiolaDerivative(below)).cwiseAbs().maxCoeff(),
      1e-6 * scaleOf(kFoam.firstPiolaDerivative(above)));
}

}  // namespace
