// Property tests of the linear tetrahedron and of warped-stiffness assembly.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/corotational_elasticity.h"
#include "deformable_sim/core/elements/mesh.h"
#include "element_test_helpers.h"

namespace dc = deformable_sim::core;
using deformable_sim::test::elasticForce;
using deformable_sim::test::stacked;

namespace {

const dc::LinearElasticMaterial kMaterial{2.0e6, 0.35, 1100.0};

dc::Mesh singleTetrahedron() {
  dc::Mesh mesh;
  mesh.positions = {{0.1, 0.0, 0.0}, {1.0, 0.1, 0.0}, {0.2, 0.9, 0.1}, {0.0, 0.2, 1.2}};
  mesh.node_numbers = {1, 2, 3, 4};
  mesh.tetrahedra = {{0, 1, 2, 3}};
  return mesh;
}

dc::Mesh smallBlock() { return dc::makeBoxMesh({0.0, 0.0, 0.0}, {0.3, 0.2, 0.1}, {3, 2, 1}); }

// A fixed, smooth, non-rigid displacement field.
Eigen::VectorXd deformation(const Eigen::VectorXd& x0, double scale) {
  Eigen::VectorXd u(x0.size());
  for (int i = 0; i < x0.size() / 3; ++i) {
    const Eigen::Vector3d p = x0.segment<3>(3 * i);
    u.segment<3>(3 * i) = scale * Eigen::Vector3d(0.3 * p.y() * p.y() + 0.1 * p.z(),
                                                  -0.2 * p.x() * p.z(), 0.25 * p.x() * p.x());
  }
  return u;
}

}  // namespace

TEST(Tetrahedron, GradientsReproduceLinearFieldsAndVolumeIsRight) {
  const dc::Mesh mesh = singleTetrahedron();
  const std::array<Eigen::Vector3d, 4> x{mesh.positions[0], mesh.positions[1], mesh.positions[2],
                                         mesh.positions[3]};
  const dc::TetrahedronRest rest = dc::computeTetrahedronRest(x);
  EXPECT_NEAR(rest.volume, dc::signedVolume(x[0], x[1], x[2], x[3]), 1e-15);
  // For any linear field phi(p) = a.p + c, sum_i phi(x_i) grad N_i = a.
  const Eigen::Vector3d a(0.7, -1.3, 2.1);
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  for (int i = 0; i < 4; ++i) gradient += (a.dot(x[i]) + 4.2) * rest.gradients[i];
  EXPECT_NEAR((gradient - a).norm(), 0.0, 1e-12);
}

TEST(Tetrahedron, StiffnessClosedFormMatchesTheVoigtProduct) {
  // The closed form the assembly uses against V B^T D B with the 6x6 Voigt elasticity matrix.
  const dc::Mesh mesh = singleTetrahedron();
  const dc::TetrahedronRest rest = dc::computeTetrahedronRest(
      {mesh.positions[0], mesh.positions[1], mesh.positions[2], mesh.positions[3]});
  const dc::ElementBlocks k = dc::elementStiffness(rest, kMaterial);
  const Eigen::Matrix<double, 6, 6> d = dc::elasticityMatrix(kMaterial);
  std::array<Eigen::Matrix<double, 6, 3>, 4> b;  // Voigt xx yy zz xy xz yz, engineering shear
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d& g = rest.gradients[i];
    b[i] << g.x(), 0, 0, 0, g.y(), 0, 0, 0, g.z(), g.y(), g.x(), 0, g.z(), 0, g.x(), 0, g.z(),
        g.y();
  }
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const Eigen::Matrix3d expected = rest.volume * b[i].transpose() * d * b[j];
      EXPECT_NEAR((k[i][j] - expected).norm(), 0.0, 1e-9 * expected.norm() + 1e-9);
    }
  }
}

TEST(Tetrahedron, ZeroForceAtRest) {
  for (const dc::Mesh& mesh : {singleTetrahedron(), smallBlock()}) {
    dc::CorotationalElasticity elasticity(mesh, kMaterial);
    const Eigen::VectorXd x0 = stacked(mesh);
    for (bool warping : {false, true}) {
      EXPECT_LT(elasticForce(elasticity, x0, warping).norm(), 1e-9) << "warping " << warping;
    }
  }
}

TEST(Tetrahedron, AssembledStiffnessIsSymmetricWithRigidModesInItsNullSpace) {
  const dc::Mesh mesh = smallBlock();
  dc::CorotationalElasticity elasticity(mesh, kMaterial);
  const Eigen::VectorXd x0 = stacked(mesh);
  elasticity.update(x0, false);
  const Eigen::MatrixXd k = elasticity.stiffness().toDense();
  EXPECT_LT((k - k.transpose()).norm(), 1e-9 * k.norm());
  // Three translations and three infinitesimal rotations w x p.
  for (int axis = 0; axis < 3; ++axis) {
    Eigen::VectorXd translation = Eigen::VectorXd::Zero(x0.size());
    Eigen::VectorXd rotation(x0.size());
    for (int i = 0; i < mesh.numNodes(); ++i) {
      translation[3 * i + axis] = 1.0;
      rotation.segment<3>(3 * i) = Eigen::Vector3d::Unit(axis).cross(mesh.positions[i]);
    }
    EXPECT_LT((k * translation).norm(), 1e-9 * k.norm()) << "translation " << axis;
    EXPECT_LT((k * rotation).norm(), 1e-9 * k.norm()) << "rotation " << axis;
  }
  // And no other zero modes: exactly six eigenvalues are (numerically) zero.
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(k);
  const Eigen::VectorXd values = eigen.eigenvalues();
  int zero = 0;
  for (int i = 0; i < values.size(); ++i) zero += std::abs(values[i]) < 1e-9 * values.maxCoeff();
  EXPECT_EQ(zero, 6);
  // Warped stiffness of a deformed state is symmetric too.
  elasticity.update(x0 + deformation(x0, 0.5), true);
  const Eigen::MatrixXd kw = elasticity.stiffness().toDense();
  EXPECT_LT((kw - kw.transpose()).norm(), 1e-9 * kw.norm());
}

TEST(Tetrahedron, AssemblyIsTheSumOfRotatedElementStiffnessesOnAnyThreadCount) {
  // K' = sum_e R_e Ke R_e^T and f0' = -sum_e R_e Ke x0_e, built here the textbook way (dense,
  // element by element) and compared with the row-by-row (vectorized) assembly.
  const dc::Mesh mesh = dc::makeBoxMesh({0.0, 0.0, 0.0}, {0.4, 0.2, 0.2}, {4, 2, 2});
  const Eigen::VectorXd x0 = stacked(mesh);
  const Eigen::VectorXd x = x0 + deformation(x0, 0.8);
  dc::CorotationalElasticity reference_rotations(mesh, kMaterial);
  reference_rotations.update(x, true);
  const int n = 3 * mesh.numNodes();
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd f0 = Eigen::VectorXd::Zero(n);
  for (size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
    const dc::Tetrahedron& t = mesh.tetrahedra[e];
    const Eigen::Matrix3d& r = reference_rotations.rotations()[e];
    const dc::ElementBlocks ke = dc::elementStiffness(reference_rotations.restData()[e], kMaterial);
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) {
        k.block<3, 3>(3 * t[a], 3 * t[b]) += r * ke[a][b] * r.transpose();
        f0.segment<3>(3 * t[a]) -= r * (ke[a][b] * x0.segment<3>(3 * t[b]));
      }
    }
  }
  for (int threads : {1, 2}) {
    dc::CorotationalElasticity elasticity(mesh, kMaterial);
    elasticity.setThreads(threads);
    elasticity.update(x, true);
    const Eigen::MatrixXd assembled = elasticity.stiffness().toDense();
    EXPECT_LT((assembled - k).norm(), 1e-13 * k.norm()) << threads << " threads";
    EXPECT_EQ(assembled, assembled.transpose()) << "symmetric bit for bit";
    EXPECT_LT((elasticity.forceOffset() - f0).norm(), 1e-13 * f0.norm()) << threads << " threads";
  }
}

TEST(Tetrahedron, RotatingADeformedBodyRotatesItsForcesOnlyWithWarping) {
  const dc::Mesh mesh = smallBlock();
  dc::CorotationalElasticity elasticity(mesh, kMaterial);
  const Eigen::VectorXd x0 = stacked(mesh);
  const Eigen::VectorXd x = x0 + deformation(x0, 0.2);
  const Eigen::Matrix3d q =
      Eigen::AngleAxisd(1.2, Eigen::Vector3d(0.2, 1.0, -0.4).normalized()).toRotationMatrix();
  const Eigen::Vector3d shift(0.5, -1.0, 2.0);
  Eigen::VectorXd qx(x.size());
  for (int i = 0; i < mesh.numNodes(); ++i) qx.segment<3>(3 * i) = q * x.segment<3>(3 * i) + shift;

  for (bool warping : {true, false}) {
    const Eigen::VectorXd f = elasticForce(elasticity, x, warping);
    const Eigen::VectorXd fq = elasticForce(elasticity, qx, warping);
    double mismatch = 0.0;
    for (int i = 0; i < mesh.numNodes(); ++i) {
      mismatch = std::max(mismatch, (fq.segment<3>(3 * i) - q * f.segment<3>(3 * i)).norm());
    }
    if (warping) {
      EXPECT_LT(mismatch, 1e-9 * f.norm());
    } else {
      EXPECT_GT(mismatch, 0.1 * f.norm()) << "linear FEM is not rotation invariant";
    }
  }
}

TEST(Tetrahedron, StiffnessIsMinusTheForceDerivative) {
  const dc::Mesh mesh = smallBlock();
  dc::CorotationalElasticity elasticity(mesh, kMaterial);
  const Eigen::VectorXd x0 = stacked(mesh);
  const Eigen::VectorXd direction =
      deformation(x0, 1.0) + Eigen::VectorXd::LinSpaced(x0.size(), -0.1, 0.1);
  const double eps = 1e-6;
  // Linear FEM: exact everywhere. Warped: at rest (where the rotation's derivative does not enter).
  for (bool warping : {false, true}) {
    const Eigen::VectorXd base = warping ? x0 : Eigen::VectorXd(x0 + deformation(x0, 0.3));
    const Eigen::VectorXd df = (elasticForce(elasticity, base + eps * direction, warping) -
                                elasticForce(elasticity, base - eps * direction, warping)) /
                               (2.0 * eps);
    elasticity.update(base, warping);
    Eigen::VectorXd k_direction(x0.size());
    elasticity.stiffness().multiply(direction, k_direction);
    EXPECT_LT((df + k_direction).norm(), 1e-6 * k_direction.norm()) << "warping " << warping;
  }
}

TEST(Tetrahedron, LumpedMassesSumToDensityTimesVolume) {
  const dc::Mesh mesh = smallBlock();
  const std::vector<double> mass = dc::lumpedMasses(mesh, kMaterial.density);
  double total = 0.0;
  for (double m : mass) total += m;
  EXPECT_NEAR(total, kMaterial.density * 0.3 * 0.2 * 0.1, 1e-12);
  EXPECT_NEAR(dc::totalVolume(mesh), 0.3 * 0.2 * 0.1, 1e-15);
}

TEST(Tetrahedron, FlattenedAndInvertedElementsGiveProperRotationsAndFiniteForces) {
  dc::Mesh mesh;
  mesh.positions = {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
  mesh.node_numbers = {1, 2, 3, 4};
  mesh.tetrahedra = {{0, 1, 2, 3}};
  dc::CorotationalElasticity elasticity(mesh, kMaterial);
  Eigen::VectorXd flat = stacked(mesh);
  flat[3 * 3 + 2] = 0.0;  // node 3 pushed into the plane of the others (z = 0)
  Eigen::VectorXd inverted = stacked(mesh);
  inverted[3 * 3 + 2] = -0.5;  // node 3 pushed through that plane
  for (const Eigen::VectorXd& x : {flat, inverted}) {
    const int bad = elasticity.update(x, true);
    EXPECT_EQ(bad, 1);
    const Eigen::Matrix3d& r = elasticity.rotations()[0];
    EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
    EXPECT_NEAR((r.transpose() * r - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
    const Eigen::VectorXd f = elasticForce(elasticity, x, true);
    EXPECT_TRUE(f.allFinite());
    // The restoring force on node 3 pushes it back up (towards positive volume).
    EXPECT_GT(f[3 * 3 + 2], 0.0);
  }
}
