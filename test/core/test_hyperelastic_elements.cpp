// A mesh's elements under the Neo-Hookean law (core/materials/hyperelastic_elements.h), typed
// over tetrahedra and hexahedra: no force at rest or under a rigid motion, forces that keep
// momentum, forces the energy's gradient and the tangent theirs, the tangent at rest the linear
// stiffness, and the projected tangent positive semi-definite where the exact one is not.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>

#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/cell.h"
#include "deformable_sim/core/elements/material.h"
#include "deformable_sim/core/elements/tetrahedron.h"
#include "deformable_sim/core/materials/hyperelastic_elements.h"

namespace dc = deformable_sim::core;

namespace {

constexpr double kE = 3.0e4, kNu = 0.45;

class HyperelasticElementsTest : public ::testing::TestWithParam<dc::BoxElement> {
 protected:
  HyperelasticElementsTest()
      : mesh_(dc::makeBoxMesh({0, 0, 0}, {0.1, 0.06, 0.04}, {2, 2, 1}, GetParam())),
        elements_(mesh_, dc::NeoHookean::fromYoungPoisson(kE, kNu)) {}

  Eigen::VectorXd rest() const {
    Eigen::VectorXd x(3 * mesh_.numNodes());
    for (int i = 0; i < mesh_.numNodes(); ++i) x.segment<3>(3 * i) = mesh_.positions[i];
    return x;
  }
  /// The rest positions deformed smoothly and by a few percent, node by node.
  Eigen::VectorXd deformed(double size) const {
    Eigen::VectorXd x = rest();
    for (int i = 0; i < mesh_.numNodes(); ++i) {
      const Eigen::Vector3d p = mesh_.positions[i];
      x.segment<3>(3 * i) += size * Eigen::Vector3d(std::sin(40 * p.y() + 3 * i), 0.5 * p.x() * 10,
                                                    std::cos(30 * p.x() + i) - 0.3 * p.z() * 10);
    }
    return x;
  }
  Eigen::VectorXd forces(const Eigen::VectorXd& x) const {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(x.size());
    elements_.addForces(x, f);
    return f;
  }

  dc::Mesh mesh_;
  dc::HyperelasticElements elements_;
};

TEST_P(HyperelasticElementsTest, NoForceAtRestOrUnderARigidMotion) {
  const Eigen::VectorXd x = rest();
  const double scale = kE * 0.04 * 0.04;  // a force of the stiffness times an element's face
  EXPECT_LT(forces(x).cwiseAbs().maxCoeff(), 1e-12 * scale);
  const Eigen::Matrix3d r(Eigen::AngleAxisd(1.2, Eigen::Vector3d(0.3, -1, 0.5).normalized()));
  Eigen::VectorXd moved = x;
  for (int i = 0; i < mesh_.numNodes(); ++i)
    moved.segment<3>(3 * i) = r * x.segment<3>(3 * i) + Eigen::Vector3d(0.5, -2, 1);
  EXPECT_LT(forces(moved).cwiseAbs().maxCoeff(), 1e-10 * scale);
  EXPECT_NEAR(elements_.energy(moved), 0.0, 1e-12 * scale * 0.1);
}

TEST_P(HyperelasticElementsTest, ForcesKeepMomentumAndAngularMomentum) {
  const Eigen::VectorXd x = deformed(0.004);
  const Eigen::VectorXd f = forces(x);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
  for (int i = 0; i < mesh_.numNodes(); ++i) {
    sum += f.segment<3>(3 * i);
    torque += x.segment<3>(3 * i).cross(f.segment<3>(3 * i));
  }
  const double scale = f.cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.0);
  EXPECT_LT(sum.norm(), 1e-12 * scale);
  EXPECT_LT(torque.norm(), 1e-12 * scale * 0.1);
}

TEST_P(HyperelasticElementsTest, ForcesAreMinusTheEnergysGradientAndTheTangentTheirs) {
  const Eigen::VectorXd x = deformed(0.006);
  const Eigen::VectorXd f = forces(x);
  const Eigen::MatrixXd k = Eigen::MatrixXd(elements_.tangent(x, false));
  const double h = 1e-7;
  Eigen::VectorXd gradient(x.size());
  Eigen::MatrixXd slopes(x.size(), x.size());
  for (int i = 0; i < x.size(); ++i) {
    Eigen::VectorXd up = x, down = x;
    up[i] += h;
    down[i] -= h;
    gradient[i] = (elements_.energy(up) - elements_.energy(down)) / (2 * h);
    slopes.col(i) = -(forces(up) - forces(down)) / (2 * h);
  }
  EXPECT_LT((f + gradient).cwiseAbs().maxCoeff(), 1e-6 * f.cwiseAbs().maxCoeff());
  EXPECT_LT((k - slopes).cwiseAbs().maxCoeff(), 1e-6 * k.cwiseAbs().maxCoeff());
  EXPECT_LT((k - k.transpose()).cwiseAbs().maxCoeff(), 1e-12 * k.cwiseAbs().maxCoeff());
}

// At rest the tangent is the linear elements' stiffness with the same E and nu.
TEST_P(HyperelasticElementsTest, TangentAtRestIsTheLinearStiffness) {
  const dc::LinearElasticMaterial material{kE, kNu, 100.0};
  const double lambda = dc::lameLambda(material), mu = dc::lameMu(material);
  Eigen::MatrixXd linear = Eigen::MatrixXd::Zero(3 * mesh_.numNodes(), 3 * mesh_.numNodes());
  for (const dc::Tetrahedron& t : mesh_.tetrahedra) {
    const dc::TetrahedronRest r =
        dc::computeTetrahedronRest({mesh_.positions[t[0]], mesh_.positions[t[1]],
                                    mesh_.positions[t[2]], mesh_.positions[t[3]]});
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        linear.block<3, 3>(3 * t[i], 3 * t[j]) +=
            dc::stiffnessBlock(lambda * r.volume, mu * r.volume, r.gradients[i], r.gradients[j]);
      }
    }
  }
  for (const dc::Cell& cell : mesh_.cells) {
    const Eigen::MatrixXd k =
        dc::cellStiffness(cell.type, dc::cellCorners(cell, mesh_.positions), lambda, mu);
    for (int i = 0; i < cell.size(); ++i) {
      for (int j = 0; j < cell.size(); ++j)
        linear.block<3, 3>(3 * cell.nodes[i], 3 * cell.nodes[j]) += k.block<3, 3>(3 * i, 3 * j);
    }
  }
  const Eigen::MatrixXd k = Eigen::MatrixXd(elements_.tangent(rest(), false));
  EXPECT_LT((k - linear).cwiseAbs().maxCoeff(), 1e-10 * linear.cwiseAbs().maxCoeff());
}

// Squashed to a fifth along z and sheared, the exact tangent has negative eigenvalues; each
// element's block projected, the whole is positive semi-definite, and still the exact one where
// that was.
TEST_P(HyperelasticElementsTest, ProjectedTangentIsPositiveSemiDefinite) {
  Eigen::VectorXd x = rest();
  for (int i = 0; i < mesh_.numNodes(); ++i) {
    const Eigen::Vector3d p = mesh_.positions[i];
    x.segment<3>(3 * i) = Eigen::Vector3d(p.x() + 2.0 * p.z(), p.y(), 0.2 * p.z());
  }
  const Eigen::MatrixXd exact = Eigen::MatrixXd(elements_.tangent(x, false));
  const Eigen::MatrixXd projected = Eigen::MatrixXd(elements_.tangent(x, true));
  const double scale = exact.cwiseAbs().maxCoeff();
  EXPECT_LT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(exact).eigenvalues().minCoeff(),
            -1e-6 * scale);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(projected).eigenvalues().minCoeff(),
            -1e-10 * scale);
  const Eigen::MatrixXd at_rest = Eigen::MatrixXd(elements_.tangent(rest(), false));
  EXPECT_LT((Eigen::MatrixXd(elements_.tangent(rest(), true)) - at_rest).cwiseAbs().maxCoeff(),
            1e-10 * at_rest.cwiseAbs().maxCoeff());
}

std::string elementName(const ::testing::TestParamInfo<dc::BoxElement>& info) {
  static const char* const kNames[] = {"Tetrahedra", "Hexahedra", "Wedges", "Pyramids"};
  return kNames[static_cast<int>(info.param)];
}

INSTANTIATE_TEST_SUITE_P(Elements, HyperelasticElementsTest,
                         ::testing::Values(dc::BoxElement::kTetrahedron,
                                           dc::BoxElement::kHexahedron, dc::BoxElement::kWedge,
                                           dc::BoxElement::kPyramid),
                         elementName);

}  // namespace
