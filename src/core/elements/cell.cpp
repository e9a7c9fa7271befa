#include "deformable_sim/core/elements/cell.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "deformable_sim/core/elements/tetrahedron.h"

namespace deformable_sim::core {

namespace {

const Eigen::Vector3d kHexahedronNodes[8] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                             {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
const Eigen::Vector3d kWedgeNodes[6] = {{0, 0, -1}, {1, 0, -1}, {0, 1, -1},
                                        {0, 0, 1},  {1, 0, 1},  {0, 1, 1}};
const Eigen::Vector3d kPyramidNodes[5] = {
    {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {0, 0, 1}};

std::vector<QuadraturePoint> hexahedronRule() {
  const double g = 1.0 / std::sqrt(3.0);
  std::vector<QuadraturePoint> rule;
  for (double z : {-g, g}) {
    for (double y : {-g, g}) {
      for (double x : {-g, g}) rule.push_back({{x, y, z}, 1.0});
    }
  }
  return rule;
}

std::vector<QuadraturePoint> wedgeRule() {
  const double g = 1.0 / std::sqrt(3.0);
  const double triangle[3][2] = {{1.0 / 6, 1.0 / 6}, {2.0 / 3, 1.0 / 6}, {1.0 / 6, 2.0 / 3}};
  std::vector<QuadraturePoint> rule;
  for (double z : {-g, g}) {
    for (const auto& p : triangle) rule.push_back({{p[0], p[1], z}, 1.0 / 6});
  }
  return rule;
}

std::vector<QuadraturePoint> pyramidRule() {
  // (u, v, w) in [-1, 1]^2 x [0, 1] maps to xi = (u (1 - w), v (1 - w), w), det = (1 - w)^2. In
  // u, v, w the pyramid's gradients are polynomials, so Gauss is exact on an affine pyramid.
  const double g = 1.0 / std::sqrt(3.0);
  const double spread = 0.5 * std::sqrt(3.0 / 5.0);
  const double w_points[3] = {0.5 - spread, 0.5, 0.5 + spread};
  const double w_weights[3] = {5.0 / 18, 8.0 / 18, 5.0 / 18};
  std::vector<QuadraturePoint> rule;
  for (int k = 0; k < 3; ++k) {
    const double w = w_points[k], shrink = 1.0 - w;
    for (double v : {-g, g}) {
      for (double u : {-g, g}) {
        rule.push_back({{u * shrink, v * shrink, w}, w_weights[k] * shrink * shrink});
      }
    }
  }
  return rule;
}

// J_ij = dx_i / dxi_j at a natural point with shape gradients `natural`.
Eigen::Matrix3d jacobian(int size, const CellVectors& corners, const CellVectors& natural) {
  Eigen::Matrix3d j = Eigen::Matrix3d::Zero();
  for (int k = 0; k < size; ++k) j.noalias() += corners[k] * natural[k].transpose();
  return j;
}

// grad_x N_k = J^-T grad_xi N_k; throws unless det J > 0.
void spatialGradients(CellType type, const CellVectors& corners, const Eigen::Vector3d& xi,
                      const char* where, CellVectors& gradients, double& det) {
  const int size = static_cast<int>(type);
  const ShapeValues shape = shapeFunctions(type, xi);
  const Eigen::Matrix3d j = jacobian(size, corners, shape.gradients);
  det = j.determinant();
  if (!(det > 0.0)) {
    throw std::invalid_argument(std::string("the isoparametric map has det J = ") +
                                std::to_string(det) + " at " + where +
                                " (inverted, flat or tangled element)");
  }
  const Eigen::Matrix3d inverse_transpose = j.inverse().transpose();
  for (int k = 0; k < size; ++k) gradients[k] = inverse_transpose * shape.gradients[k];
}

}  // namespace

Eigen::Vector3d naturalNode(CellType type, int i) {
  switch (type) {
    case CellType::kHexahedron:
      return kHexahedronNodes[i];
    case CellType::kWedge:
      return kWedgeNodes[i];
    case CellType::kPyramid:
      return kPyramidNodes[i];
  }
  return Eigen::Vector3d::Zero();
}

ShapeValues shapeFunctions(CellType type, const Eigen::Vector3d& xi) {
  ShapeValues s;
  const double x = xi[0], y = xi[1], z = xi[2];
  switch (type) {
    case CellType::kHexahedron:
      for (int k = 0; k < 8; ++k) {
        const Eigen::Vector3d& c = kHexahedronNodes[k];
        const double fx = 1 + c[0] * x, fy = 1 + c[1] * y, fz = 1 + c[2] * z;
        s.values[k] = 0.125 * fx * fy * fz;
        s.gradients[k] = 0.125 * Eigen::Vector3d(c[0] * fy * fz, fx * c[1] * fz, fx * fy * c[2]);
      }
      break;
    case CellType::kWedge: {
      const double l[3] = {1 - x - y, x, y};
      const Eigen::Vector2d dl[3] = {{-1, -1}, {1, 0}, {0, 1}};
      for (int k = 0; k < 6; ++k) {
        const double c = k < 3 ? -1.0 : 1.0, fz = 0.5 * (1 + c * z);
        s.values[k] = l[k % 3] * fz;
        s.gradients[k] = Eigen::Vector3d(dl[k % 3][0] * fz, dl[k % 3][1] * fz, 0.5 * c * l[k % 3]);
      }
      break;
    }
    case CellType::kPyramid: {
      // r and its derivatives, all bounded on the natural pyramid; zero at the apex.
      const double apex_distance = 1 - z;
      double r = 0, rx = 0, ry = 0, rz = 0;
      if (apex_distance > 0) {
        r = x * y * z / apex_distance;
        rx = y * z / apex_distance;
        ry = x * z / apex_distance;
        rz = x * y / (apex_distance * apex_distance);
      }
      for (int k = 0; k < 4; ++k) {
        const double a = kPyramidNodes[k][0], b = kPyramidNodes[k][1];
        s.values[k] = 0.25 * ((1 + a * x) * (1 + b * y) - z + a * b * r);
        s.gradients[k] = 0.25 * Eigen::Vector3d(a * (1 + b * y) + a * b * rx,
                                                b * (1 + a * x) + a * b * ry, -1 + a * b * rz);
      }
      s.values[4] = z;
      s.gradients[4] = Eigen::Vector3d(0, 0, 1);
      break;
    }
  }
  return s;
}

Eigen::Vector3d naturalCentre(CellType type) {
  switch (type) {
    case CellType::kHexahedron:
      return Eigen::Vector3d::Zero();
    case CellType::kWedge:
      return Eigen::Vector3d(1.0 / 3, 1.0 / 3, 0);
    case CellType::kPyramid:
      return Eigen::Vector3d(0, 0, 0.25);
  }
  return Eigen::Vector3d::Zero();
}

const std::vector<QuadraturePoint>& quadrature(CellType type) {
  static const std::vector<QuadraturePoint> hexahedron = hexahedronRule();
  static const std::vector<QuadraturePoint> wedge = wedgeRule();
  static const std::vector<QuadraturePoint> pyramid = pyramidRule();
  switch (type) {
    case CellType::kHexahedron:
      return hexahedron;
    case CellType::kWedge:
      return wedge;
    case CellType::kPyramid:
      return pyramid;
  }
  return hexahedron;
}

CellVectors cellCorners(const Cell& cell, const std::vector<Eigen::Vector3d>& positions) {
  CellVectors corners;
  for (int k = 0; k < cell.size(); ++k) corners[k] = positions[cell.nodes[k]];
  return corners;
}

std::vector<QuadraturePoint> materialQuadrature(CellType type, const OctantFractions* fractions) {
  std::vector<QuadraturePoint> rule = quadrature(type);
  if (!fractions) return rule;
  const OctantFractions& f = *fractions;
  const bool even = std::all_of(f.begin(), f.end(), [&](double g) { return g == f[0]; });
  if (even || type != CellType::kHexahedron) {
    double mean = 0.0;
    for (double g : f) mean += g / 8.0;
    for (QuadraturePoint& q : rule) q.weight *= mean;
    return rule;
  }
  // Octant o spans xi in [-1, 0] or [0, 1] along each axis (bit k of o set: the upper half);
  // Gauss's points sit at its centre +- 1 / (2 sqrt 3), weight 1 / 8 of its natural volume 1.
  const double offset = 0.5 / std::sqrt(3.0);
  rule.clear();
  for (int o = 0; o < 8; ++o) {
    if (!(f[o] > 0.0)) continue;
    const Eigen::Vector3d centre(o & 1 ? 0.5 : -0.5, o & 2 ? 0.5 : -0.5, o & 4 ? 0.5 : -0.5);
    for (int p = 0; p < 8; ++p) {
      const Eigen::Vector3d sign(p & 1 ? 1 : -1, p & 2 ? 1 : -1, p & 4 ? 1 : -1);
      rule.push_back({centre + offset * sign, 0.125 * f[o]});
    }
  }
  return rule;
}

CellRest computeCellRest(CellType type, const CellVectors& corners,
                         const OctantFractions* fractions) {
  const int size = static_cast<int>(type);
  CellRest rest;
  double det = 0.0;
  spatialGradients(type, corners, naturalCentre(type), "the centre", rest.centre_gradients, det);
  CellVectors unused;
  for (const QuadraturePoint& q : materialQuadrature(type, fractions)) {
    spatialGradients(type, corners, q.xi, "an integration point", unused, det);
    const ShapeValues shape = shapeFunctions(type, q.xi);
    const double volume = q.weight * det;
    rest.volume += volume;
    for (int k = 0; k < size; ++k) rest.shape_integrals[k] += volume * shape.values[k];
  }
  return rest;
}

std::pair<double, double> jacobianRange(CellType type, const CellVectors& corners) {
  const int size = static_cast<int>(type);
  auto det = [&](const Eigen::Vector3d& xi) {
    return jacobian(size, corners, shapeFunctions(type, xi).gradients).determinant();
  };
  double low = det(naturalCentre(type)), high = low;
  for (const QuadraturePoint& q : quadrature(type)) {
    const double d = det(q.xi);
    low = std::min(low, d);
    high = std::max(high, d);
  }
  return {low, high};
}

Cell mirrored(const Cell& cell) {
  Cell m = cell;
  const std::array<int, 8>& n = cell.nodes;
  switch (cell.type) {
    case CellType::kHexahedron:
      m.nodes = {n[4], n[5], n[6], n[7], n[0], n[1], n[2], n[3]};
      break;
    case CellType::kWedge:
      m.nodes = {n[3], n[4], n[5], n[0], n[1], n[2], 0, 0};
      break;
    case CellType::kPyramid:
      m.nodes = {n[0], n[3], n[2], n[1], n[4], 0, 0, 0};
      break;
  }
  return m;
}

Eigen::MatrixXd cellStiffness(CellType type, const CellVectors& corners, double lambda, double mu,
                              const OctantFractions* fractions) {
  const int size = static_cast<int>(type);
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(3 * size, 3 * size);
  CellVectors g;
  double det = 0.0;
  for (const QuadraturePoint& q : materialQuadrature(type, fractions)) {
    spatialGradients(type, corners, q.xi, "an integration point", g, det);
    const double volume = q.weight * det;
    for (int i = 0; i < size; ++i) {
      for (int j = 0; j < size; ++j) {
        k.block<3, 3>(3 * i, 3 * j) += stiffnessBlock(lambda * volume, mu * volume, g[i], g[j]);
      }
    }
  }
  return k;
}

Eigen::Matrix3d cellDeformationGradient(const CellRest& rest, int size, const CellVectors& x) {
  Eigen::Matrix3d f = Eigen::Matrix3d::Zero();
  for (int k = 0; k < size; ++k) f.noalias() += x[k] * rest.centre_gradients[k].transpose();
  return f;
}

}  // namespace deformable_sim::core
