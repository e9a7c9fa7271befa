// Property tests of the pyramid, wedge and hexahedron: the same as the tetrahedron's (rest state,
// symmetry, rigid modes, rotation, finite differences, mass), plus what only isoparametric
// elements need (partition of unity, exact quadrature, the patch test).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <string>

#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/cell.h"
#include "deformable_sim/core/elements/corotational_elasticity.h"
#include "deformable_sim/core/elements/mesh.h"
#include "element_test_helpers.h"

namespace dc = deformable_sim::core;
using deformable_sim::test::elasticForce;
using deformable_sim::test::stacked;

namespace {

const dc::LinearElasticMaterial kMaterial{2.0e6, 0.35, 1100.0};

struct Kind {
  dc::CellType type;
  dc::BoxElement box;
  double natural_volume;
  const char* name;
};

const Kind kKinds[] = {{dc::CellType::kHexahedron, dc::BoxElement::kHexahedron, 8.0, "Hexahedron"},
                       {dc::CellType::kWedge, dc::BoxElement::kWedge, 1.0, "Wedge"},
                       {dc::CellType::kPyramid, dc::BoxElement::kPyramid, 4.0 / 3, "Pyramid"}};

class CellTest : public ::testing::TestWithParam<Kind> {
 protected:
  dc::CellType type() const { return GetParam().type; }
  int size() const { return static_cast<int>(type()); }

  // A point well inside the natural element.
  Eigen::Vector3d interiorPoint(const Eigen::Vector3d& random) const {
    switch (type()) {
      case dc::CellType::kHexahedron:
        return 0.9 * random;
      case dc::CellType::kWedge: {
        const Eigen::Vector3d p = 0.5 * (random.array() + 1.0);  // in [0, 1]^3
        return {0.45 * p.x(), 0.45 * p.y(), random.z() * 0.9};
      }
      case dc::CellType::kPyramid: {
        const double z = 0.05 + 0.8 * 0.5 * (random.z() + 1.0);
        return {0.9 * (1 - z) * random.x(), 0.9 * (1 - z) * random.y(), z};
      }
    }
    return Eigen::Vector3d::Zero();
  }

  // One element: the natural element under an affine map A xi + b.
  dc::Mesh affineElement(const Eigen::Matrix3d& a, const Eigen::Vector3d& b) const {
    dc::Mesh mesh;
    dc::Cell cell{type(), {}};
    for (int k = 0; k < size(); ++k) {
      mesh.positions.push_back(a * dc::naturalNode(type(), k) + b);
      mesh.node_numbers.push_back(k + 1);
      cell.nodes[k] = k;
    }
    mesh.cells.push_back(cell);
    return mesh;
  }

  static Eigen::Matrix3d someAffineMap() {
    Eigen::Matrix3d a;
    a << 0.31, 0.04, -0.02, 0.03, 0.27, 0.05, -0.01, 0.02, 0.22;
    return a;
  }

  // An element that is not an affine image: the affine element with its nodes moved a little.
  dc::Mesh distortedElement() const {
    dc::Mesh mesh = affineElement(someAffineMap(), {0.1, -0.2, 0.3});
    for (int k = 0; k < size(); ++k) {
      mesh.positions[k] +=
          0.02 * Eigen::Vector3d(std::sin(3.0 * k), std::cos(5.0 * k), std::sin(k + 0.5));
    }
    return mesh;
  }

  dc::Mesh block() const {
    return dc::makeBoxMesh({0, 0, 0}, {0.3, 0.2, 0.2}, {3, 2, 2}, GetParam().box);
  }
};

}  // namespace

TEST_P(CellTest, ShapeFunctionsInterpolateAndReproduceLinearFields) {
  for (int k = 0; k < size(); ++k) {
    const dc::ShapeValues at_node = dc::shapeFunctions(type(), dc::naturalNode(type(), k));
    for (int m = 0; m < size(); ++m) EXPECT_NEAR(at_node.values[m], k == m ? 1.0 : 0.0, 1e-15);
  }
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d xi = interiorPoint(Eigen::Vector3d::Random());
    const dc::ShapeValues s = dc::shapeFunctions(type(), xi);
    double sum = 0.0;
    Eigen::Vector3d position = Eigen::Vector3d::Zero(), gradient_sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d position_gradient = Eigen::Matrix3d::Zero();
    for (int k = 0; k < size(); ++k) {
      sum += s.values[k];
      position += s.values[k] * dc::naturalNode(type(), k);
      gradient_sum += s.gradients[k];
      position_gradient += dc::naturalNode(type(), k) * s.gradients[k].transpose();
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
    EXPECT_LT((position - xi).norm(), 1e-14);  // linear completeness
    EXPECT_LT(gradient_sum.norm(), 1e-14);
    EXPECT_LT((position_gradient - Eigen::Matrix3d::Identity()).norm(), 1e-13);
    // The gradients are those of the values (central differences).
    const double h = 1e-6;
    for (int d = 0; d < 3; ++d) {
      const Eigen::Vector3d step = h * Eigen::Vector3d::Unit(d);
      const dc::ShapeValues plus = dc::shapeFunctions(type(), xi + step);
      const dc::ShapeValues minus = dc::shapeFunctions(type(), xi - step);
      for (int k = 0; k < size(); ++k) {
        EXPECT_NEAR((plus.values[k] - minus.values[k]) / (2 * h), s.gradients[k][d], 1e-8);
      }
    }
  }
}

TEST_P(CellTest, QuadratureGivesTheExactVolumeAndMassOfAnAffineElement) {
  double weights = 0.0;
  for (const dc::QuadraturePoint& q : dc::quadrature(type())) weights += q.weight;
  EXPECT_NEAR(weights, GetParam().natural_volume, 1e-14);
  const Eigen::Matrix3d a = someAffineMap();
  const dc::Mesh mesh = affineElement(a, {1, 2, 3});
  const double volume = a.determinant() * GetParam().natural_volume;
  const dc::CellRest rest =
      dc::computeCellRest(type(), dc::cellCorners(mesh.cells[0], mesh.positions));
  EXPECT_NEAR(rest.volume, volume, 1e-15);
  EXPECT_NEAR(dc::totalVolume(mesh), volume, 1e-15);
  double shares = 0.0;
  for (int k = 0; k < size(); ++k) {
    EXPECT_GT(rest.shape_integrals[k], 0.0) << "node " << k;
    shares += rest.shape_integrals[k];
  }
  EXPECT_NEAR(shares, volume, 1e-15);
  const std::vector<double> mass = dc::lumpedMasses(mesh, kMaterial.density);
  double total = 0.0;
  for (double m : mass) total += m;
  EXPECT_NEAR(total, kMaterial.density * volume, 1e-12);
}

TEST_P(CellTest, StiffnessIsSymmetricWithExactlySixRigidModes) {
  const dc::Mesh mesh = distortedElement();
  const Eigen::MatrixXd k =
      dc::cellStiffness(type(), dc::cellCorners(mesh.cells[0], mesh.positions),
                        dc::lameLambda(kMaterial), dc::lameMu(kMaterial));
  EXPECT_LT((k - k.transpose()).norm(), 1e-12 * k.norm());
  // Translations and infinitesimal rotations about the centroid strain nothing.
  for (int mode = 0; mode < 6; ++mode) {
    Eigen::VectorXd u(3 * size());
    for (int n = 0; n < size(); ++n) {
      u.segment<3>(3 * n) = mode < 3 ? Eigen::Vector3d::Unit(mode)
                                     : Eigen::Vector3d::Unit(mode - 3).cross(mesh.positions[n]);
    }
    EXPECT_LT((k * u).norm(), 1e-9 * k.norm() * u.norm()) << "mode " << mode;
  }
  // ... and nothing else: full integration leaves no spurious (hourglass) mode.
  const Eigen::VectorXd eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(k).eigenvalues();
  for (int m = 0; m < 6; ++m) EXPECT_LT(std::abs(eigenvalues[m]), 1e-9 * eigenvalues.maxCoeff());
  EXPECT_GT(eigenvalues[6], 1e-3 * eigenvalues.maxCoeff());
}

TEST_P(CellTest, AMeshPassesThePatchTest) {
  // A homogeneous strain is a uniform stress: every node not on the boundary is in equilibrium.
  const dc::Mesh mesh = block();
  dc::CorotationalElasticity elasticity(mesh, kMaterial);
  Eigen::Matrix3d g;
  g << 0.01, 0.002, -0.003, 0.001, -0.02, 0.004, 0.0, 0.003, 0.015;
  Eigen::VectorXd x = stacked(mesh);
  for (int i = 0; i < mesh.numNodes(); ++i) x.segment<3>(3 * i) += g * mesh.positions[i];
  const Eigen::VectorXd f = elasticForce(elasticity, x, false);
  int interior = 0;
  for (int i = 0; i < mesh.numNodes(); ++i) {
    const Eigen::Vector3d& p = mesh.positions[i];
    const bool inside = p.x() > 1e-9 && p.x() < 0.3 - 1e-9 && p.y() > 1e-9 && p.y() < 0.2 - 1e-9 &&
                        p.z() > 1e-9 && p.z() < 0.2 - 1e-9;
    if (!inside) continue;
    ++interior;
    EXPECT_LT(f.segment<3>(3 * i).norm(), 1e-9 * f.norm()) << "node " << i;
  }
  EXPECT_GT(interior, 0);
  EXPECT_GT(f.norm(), 1.0);  // the boundary does carry the stress
}

TEST_P(CellTest, AssembledStiffnessIsSymmetricAndMinusTheForceDerivative) {
  const dc::Mesh mesh = block();
  dc::CorotationalElasticity elasticity(mesh, kMaterial);
  Eigen::VectorXd x = stacked(mesh);
  for (int i = 0; i < x.size(); ++i) x[i] += 0.003 * std::sin(1.7 * i);
  const Eigen::VectorXd f = elasticForce(elasticity, x, true);
  const Eigen::MatrixXd k = elasticity.stiffness().toDense();
  EXPECT_LT((k - k.transpose()).norm(), 1e-12 * k.norm());
  // With the rotations held, f = -(K' x + f0') and the energy's gradient is -f.
  const double h = 1e-7;
  for (int d = 0; d < x.size(); d += 7) {
    Eigen::VectorXd plus = x, minus = x;
    plus[d] += h;
    minus[d] -= h;
    const double derivative =
        (elasticity.elasticEnergy(plus) - elasticity.elasticEnergy(minus)) / (2 * h);
    EXPECT_NEAR(derivative, -f[d], 1e-6 * f.norm()) << "dof " << d;
  }
}

TEST_P(CellTest, RotatingADeformedBodyRotatesItsForces) {
  const dc::Mesh mesh = block();
  dc::CorotationalElasticity elasticity(mesh, kMaterial);
  const Eigen::VectorXd rest = stacked(mesh);
  EXPECT_LT(elasticForce(elasticity, rest, true).norm(), 1e-9);  // zero force at rest
  Eigen::VectorXd deformed = rest;
  for (int i = 0; i < rest.size(); ++i) deformed[i] += 0.002 * std::cos(0.9 * i);
  const Eigen::VectorXd f = elasticForce(elasticity, deformed, true);
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Eigen::VectorXd turned(rest.size());
  for (int i = 0; i < mesh.numNodes(); ++i)
    turned.segment<3>(3 * i) = r * deformed.segment<3>(3 * i);
  const Eigen::VectorXd g = elasticForce(elasticity, turned, true);
  for (int i = 0; i < mesh.numNodes(); ++i) {
    EXPECT_LT((g.segment<3>(3 * i) - r * f.segment<3>(3 * i)).norm(), 1e-9 * f.norm());
  }
  // A rigid rotation alone gives no force.
  for (int i = 0; i < mesh.numNodes(); ++i) turned.segment<3>(3 * i) = r * rest.segment<3>(3 * i);
  EXPECT_LT(elasticForce(elasticity, turned, true).norm(), 1e-9);
}

TEST_P(CellTest, BoundaryIsClosedAndOutward) {
  // The divergence theorem: the boundary's outward area vectors sum to zero, and the flux of
  // the field x through it is three times the volume.
  const dc::Mesh mesh = block();
  Eigen::Vector3d area = Eigen::Vector3d::Zero();
  double flux = 0.0;
  for (const dc::Triangle& t : dc::extractSurface(mesh)) {
    const Eigen::Vector3d& a = mesh.positions[t[0]];
    const Eigen::Vector3d n = 0.5 * (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a);
    area += n;
    flux += n.dot((a + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0);
  }
  EXPECT_LT(area.norm(), 1e-15);
  EXPECT_NEAR(flux, 3.0 * 0.3 * 0.2 * 0.2, 1e-14);
  EXPECT_NEAR(dc::totalVolume(mesh), 0.3 * 0.2 * 0.2, 1e-15);
  // Quadrilaterals stay whole where the elements have them.
  int quads = 0;
  for (const dc::Face& f : dc::extractBoundary(mesh)) quads += f.size() == 4;
  EXPECT_GT(quads, 0);
}

TEST_P(CellTest, AnInvertedCellIsRefusedWithItsReason) {
  dc::Mesh mesh = affineElement(someAffineMap(), {0, 0, 0});
  std::swap(mesh.positions[0], mesh.positions[1]);
  try {
    dc::computeCellRest(type(), dc::cellCorners(mesh.cells[0], mesh.positions));
    FAIL() << "an inverted " << GetParam().name << " was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("det J"), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(AllTypes, CellTest, ::testing::ValuesIn(kKinds),
                         [](const ::testing::TestParamInfo<Kind>& info) {
                           return info.param.name;
                         });
