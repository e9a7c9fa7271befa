// The structured box mesh, for every element type: nodes on the grid in x-fastest order, every
// element positive and the volumes summing to the box's, a conforming mesh whose only boundary is
// the box's surface, the tetrahedra's mirror symmetries, and what it refuses.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/core/geometry/triangle_mesh.h"
#include "surface_meters.h"
#include "thrown_message.h"

namespace dc = deformable_sim::core;
namespace dt = deformable_sim::test;

namespace {

const Eigen::Vector3d kMin(-0.2, 0.1, 0.3), kMax(0.4, 0.4, 0.5);
const Eigen::Vector3i kCells(3, 2, 2);

constexpr std::array<dc::BoxElement, 4> kElements = {
    dc::BoxElement::kTetrahedron, dc::BoxElement::kHexahedron, dc::BoxElement::kWedge,
    dc::BoxElement::kPyramid};

std::string name(dc::BoxElement element) {
  switch (element) {
    case dc::BoxElement::kTetrahedron:
      return "tetrahedra";
    case dc::BoxElement::kHexahedron:
      return "hexahedra";
    case dc::BoxElement::kWedge:
      return "wedges";
    case dc::BoxElement::kPyramid:
      return "pyramids";
  }
  return "";
}

// An element's volume from tetrahedra of its corners (an independent decomposition, not the
// cell integration): positive only if its nodes are in the documented order.
double elementVolume(const std::vector<Eigen::Vector3d>& x, const dc::Cell& cell) {
  const auto& n = cell.nodes;
  auto tet = [&](int a, int b, int c, int d) { return dc::signedVolume(x[a], x[b], x[c], x[d]); };
  switch (cell.type) {
    case dc::CellType::kPyramid:  // base counter-clockwise seen from the apex
      return tet(n[0], n[1], n[2], n[4]) + tet(n[0], n[2], n[3], n[4]);
    case dc::CellType::kWedge:  // an upright prism: three times the tetrahedron on its base
      return 3.0 * tet(n[0], n[1], n[2], n[3]);
    case dc::CellType::kHexahedron:  // a brick: six times its corner tetrahedron
      return 6.0 * tet(n[0], n[1], n[3], n[4]);
  }
  return 0.0;
}

// The mesh's boundary as a triangle surface over its nodes.
dc::TriangleMesh boundarySurface(const dc::Mesh& mesh) {
  dc::TriangleMesh surface;
  surface.vertices = mesh.positions;
  for (const dc::Triangle& t : dc::extractSurface(mesh))
    surface.triangles.emplace_back(t[0], t[1], t[2]);
  return surface;
}

// The tetrahedra as sets of node positions, mapped by `map`.
template <typename Map>
std::set<std::array<std::array<double, 3>, 4>> tetrahedraAsPoints(const dc::Mesh& mesh, Map map) {
  std::set<std::array<std::array<double, 3>, 4>> result;
  for (const dc::Tetrahedron& t : mesh.tetrahedra) {
    std::array<std::array<double, 3>, 4> corners;
    for (int c = 0; c < 4; ++c) {
      const Eigen::Vector3d p = map(mesh.positions[t[c]]);
      corners[c] = {p.x(), p.y(), p.z()};
    }
    std::sort(corners.begin(), corners.end());
    result.insert(corners);
  }
  return result;
}

}  // namespace

TEST(BoxMesh, GridNodesComeXFastestNumberedFromOne) {
  for (dc::BoxElement element : kElements) {
    const dc::Mesh mesh = dc::makeBoxMesh(kMin, kMax, kCells, element);
    const Eigen::Vector3d h = (kMax - kMin).cwiseQuotient(kCells.cast<double>());
    const int grid_nodes = 4 * 3 * 3;
    const int centres = element == dc::BoxElement::kPyramid ? kCells.prod() : 0;
    ASSERT_EQ(mesh.numNodes(), grid_nodes + centres) << name(element);
    ASSERT_EQ(mesh.node_numbers.size(), mesh.positions.size());
    for (int k = 0, node = 0; k < 3; ++k) {
      for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 4; ++i, ++node) {
          EXPECT_NEAR(
              (mesh.positions[node] - (kMin + Eigen::Vector3d(i, j, k).cwiseProduct(h))).norm(),
              0.0, 1e-15)
              << name(element) << " node " << node;
        }
      }
    }
    for (int i = 0; i < mesh.numNodes(); ++i) EXPECT_EQ(mesh.node_numbers[i], i + 1);
    // The last corner is the box's far corner.
    EXPECT_NEAR((mesh.positions[grid_nodes - 1] - kMax).norm(), 0.0, 1e-15) << name(element);
  }
}

// The nodes are placed at min + i h with h = (max - min) / cells, so the far side lands where
// that rounding puts it: here at x = 0.40000000000000008 for max.x = 0.4. The mesh then pokes an
// ulp out of [min, max], and a closed selection box whose face is exactly at max (the box's own
// face, as a scene file would write it) misses those nodes.
TEST(BoxMesh, DISABLED_TheFarSideIsExactlyAtMax) {
  const dc::Mesh mesh = dc::makeBoxMesh(kMin, kMax, kCells);
  EXPECT_EQ(mesh.positions[4 * 3 * 3 - 1], kMax);
  for (const Eigen::Vector3d& p : mesh.positions) {
    EXPECT_TRUE((p.array() <= kMax.array()).all()) << p.transpose();
  }
}

TEST(BoxMesh, PyramidApexesAreTheCellCentresAfterTheGrid) {
  const dc::Mesh mesh = dc::makeBoxMesh(kMin, kMax, kCells, dc::BoxElement::kPyramid);
  const Eigen::Vector3d h = (kMax - kMin).cwiseQuotient(kCells.cast<double>());
  ASSERT_EQ(mesh.cells.size(), 6u * kCells.prod());
  for (int k = 0, cell = 0; k < kCells.z(); ++k) {
    for (int j = 0; j < kCells.y(); ++j) {
      for (int i = 0; i < kCells.x(); ++i, ++cell) {
        const int apex = 36 + cell;
        const Eigen::Vector3d centre =
            kMin + (Eigen::Vector3d(i, j, k) + Eigen::Vector3d::Constant(0.5)).cwiseProduct(h);
        EXPECT_NEAR((mesh.positions[apex] - centre).norm(), 0.0, 1e-15) << cell;
        for (int p = 0; p < 6; ++p) EXPECT_EQ(mesh.cells[6 * cell + p].nodes[4], apex);
      }
    }
  }
}

TEST(BoxMesh, ElementsArePositiveAndFillTheBox) {
  const double box_volume = (kMax - kMin).prod();
  const int cubes = kCells.prod();
  for (dc::BoxElement element : kElements) {
    const dc::Mesh mesh = dc::makeBoxMesh(kMin, kMax, kCells, element);
    double sum = 0.0;
    if (element == dc::BoxElement::kTetrahedron) {
      EXPECT_EQ(mesh.numTetrahedra(), 6 * cubes);
      EXPECT_TRUE(mesh.cells.empty());
      for (const dc::Tetrahedron& t : mesh.tetrahedra) {
        const double v = dc::signedVolume(mesh.positions, t);
        EXPECT_NEAR(v, box_volume / cubes / 6.0, 1e-15);  // the six of a cube are equal
        sum += v;
      }
    } else {
      EXPECT_EQ(mesh.numTetrahedra(), 0);
      const int per_cube = element == dc::BoxElement::kHexahedron ? 1
                           : element == dc::BoxElement::kWedge    ? 2
                                                                  : 6;
      const dc::CellType type = element == dc::BoxElement::kHexahedron ? dc::CellType::kHexahedron
                                : element == dc::BoxElement::kWedge    ? dc::CellType::kWedge
                                                                       : dc::CellType::kPyramid;
      EXPECT_EQ(static_cast<int>(mesh.cells.size()), per_cube * cubes) << name(element);
      for (const dc::Cell& cell : mesh.cells) {
        EXPECT_EQ(cell.type, type);
        const double v = elementVolume(mesh.positions, cell);
        EXPECT_GT(v, 0.0) << name(element);
        sum += v;
      }
    }
    EXPECT_NEAR(sum, box_volume, 1e-15) << name(element);
    EXPECT_NEAR(dc::totalVolume(mesh), box_volume, 1e-15) << name(element);
  }
}

TEST(BoxMesh, TheOnlyBoundaryIsTheBoxsSurfaceFacingOut) {
  // Elements that failed to share a face would leave it on the boundary, inside the box.
  const Eigen::Vector3d size = kMax - kMin;
  const double area = 2.0 * (size.x() * size.y() + size.y() * size.z() + size.z() * size.x());
  for (dc::BoxElement element : kElements) {
    const dc::Mesh mesh = dc::makeBoxMesh(kMin, kMax, kCells, element);
    for (const dc::Face& face : dc::extractBoundary(mesh)) {
      for (int k = 0; k < face.size(); ++k) {
        const Eigen::Vector3d& p = mesh.positions[face.nodes[k]];
        const bool on_surface = ((p - kMin).cwiseAbs().minCoeff() < 1e-15) ||
                                ((p - kMax).cwiseAbs().minCoeff() < 1e-15);
        EXPECT_TRUE(on_surface) << name(element) << " " << p.transpose();
      }
    }
    const dc::TriangleMesh surface = boundarySurface(mesh);
    EXPECT_NEAR(dt::surfaceArea(surface), area, 1e-14) << name(element);
    EXPECT_NEAR(dt::divergenceVolume(surface), size.prod(), 1e-15) << name(element);
  }
}

TEST(BoxMesh, TetrahedraHaveTheBoxsMirrorSymmetriesForEvenCellCounts) {
  // A symmetric load must give a symmetric response: reflecting the mesh in each of the box's
  // mid-planes gives the same tetrahedra.
  // Unit cubes: the reflected coordinates are exact.
  const Eigen::Vector3d min(-2.0, 0.0, 1.0), max(2.0, 2.0, 3.0);
  const dc::Mesh mesh = dc::makeBoxMesh(min, max, {4, 2, 2});
  const auto same = tetrahedraAsPoints(mesh, [](const Eigen::Vector3d& p) { return p; });
  for (int axis = 0; axis < 3; ++axis) {
    const auto mirrored = tetrahedraAsPoints(mesh, [&](Eigen::Vector3d p) {
      p[axis] = min[axis] + max[axis] - p[axis];
      return p;
    });
    EXPECT_EQ(mirrored, same) << "axis " << axis;
  }
}

TEST(BoxMesh, TheTetrahedraOfACubeAreOfTheDocumentedQuality) {
  // Each is a path tetrahedron of the cube, edges 1, 1, 1, sqrt 2, sqrt 2, sqrt 3 for a unit
  // cube: quality 6 sqrt(2) (1/6) / (10/6)^(3/2).
  const dc::Mesh mesh = dc::makeBoxMesh({0, 0, 0}, {2, 2, 2}, {2, 2, 2});
  const double expected = std::sqrt(2.0) / std::pow(10.0 / 6.0, 1.5);
  for (const dc::Tetrahedron& t : mesh.tetrahedra) {
    EXPECT_NEAR(dc::shapeQuality(mesh.positions, t), expected, 1e-14);
  }
  EXPECT_NEAR(expected, 0.66, 0.005);
}

TEST(BoxMesh, RefusesAnEmptyBoxTooFewOrTooManyCells) {
  auto refusal = [](const Eigen::Vector3d& min, const Eigen::Vector3d& max,
                    const Eigen::Vector3i& cells) {
    return dt::thrownMessage<std::invalid_argument>([&] { dc::makeBoxMesh(min, max, cells); },
                                                    "accepted");
  };
  const std::string empty = "box mesh: min must be below max on every axis";
  EXPECT_EQ(refusal({0, 0, 0}, {1, 0, 1}, {1, 1, 1}), empty);
  EXPECT_EQ(refusal({0, 0, 0}, {1, 1, -1}, {1, 1, 1}), empty);
  EXPECT_EQ(refusal({0, 0, NAN}, {1, 1, 1}, {1, 1, 1}), empty);
  EXPECT_EQ(refusal({0, 0, 0}, {1, INFINITY, 1}, {1, 1, 1}), empty);
  EXPECT_EQ(refusal({0, 0, 0}, {1, 1, 1}, {1, 0, 1}), "box mesh: needs at least one cell per axis");
  EXPECT_EQ(refusal({0, 0, 0}, {1, 1, 1}, {1, 1, -3}),
            "box mesh: needs at least one cell per axis");
  EXPECT_EQ(refusal({0, 0, 0}, {1, 1, 1}, {1001, 1000, 1}), "box mesh: more than 1000000 cells");
  // Whose product overflows an int: still refused, not wrapped round to something small.
  EXPECT_EQ(refusal({0, 0, 0}, {1, 1, 1}, {65536, 65536, 2}), "box mesh: more than 1000000 cells");
}
