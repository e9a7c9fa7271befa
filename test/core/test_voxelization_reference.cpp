// Voxelization against a brute-force reference, the refusal of hostile grids before anything is
// allocated, and its progress reports.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "deformable_sim/core/geometry/hole_caps.h"
#include "deformable_sim/core/geometry/winding_number.h"
#include "deformable_sim/core/surface_bodies/box_occupancy.h"
#include "deformable_sim/core/surface_bodies/grid_inside.h"
#include "deformable_sim/core/surface_bodies/ray_winding.h"
#include "deformable_sim/core/surface_bodies/voxelization.h"
#include "surface_test_helpers.h"

namespace dc = deformable_sim::core;
namespace dt = deformable_sim::test;

namespace {

// Per grid cell, the octant fractions from `inside` (below: the exact winding number, every solid
// angle summed):
// at the centre of each of the cell's (2^levels)^3 parts (`every_part`), or, as voxelize cuts a
// cell, only where a triangle may cross (an open surface's winding number varies across a part
// that no triangle crosses, which voxelize decides by its centre). No tree, no rays.
std::vector<dc::OctantFractions> bruteForceFractions(const dc::TriangleMesh& surface,
                                                     const dc::VoxelGrid& grid, int levels,
                                                     bool every_part,
                                                     const dc::InsideTest& inside) {
  const int n = 1 << levels, half = n / 2;
  const double part = grid.cell_size / n;
  std::vector<dc::OctantFractions> fractions(grid.numCells());
  const std::vector<std::vector<int>> bins = dc::binTriangles(surface, grid);
  for (int k = 0; k < grid.cells.z(); ++k) {
    for (int j = 0; j < grid.cells.y(); ++j) {
      for (int i = 0; i < grid.cells.x(); ++i) {
        const long index = grid.cellIndex({i, j, k});
        dc::OctantFractions& f = fractions[index];
        f.fill(0.0);
        const Eigen::Vector3d min = grid.cellMin({i, j, k});
        // A cell no triangle comes near is all in or all out (the exact winding number of the
        // closed shapes here is constant off the surface): its centre decides, to save time.
        if (bins[index].empty()) {
          f.fill(inside(min.array() + 0.5 * grid.cell_size));
          continue;
        }
        if (!every_part) {
          f = dc::octantFractions(surface, inside, bins[index], min, grid.cell_size, levels);
          continue;
        }
        for (int c = 0; c < n; ++c) {
          for (int b = 0; b < n; ++b) {
            for (int a = 0; a < n; ++a) {
              const Eigen::Vector3d q = min + part * Eigen::Vector3d(a + 0.5, b + 0.5, c + 0.5);
              if (!inside(q)) continue;
              const int octant = (a >= half) + 2 * (b >= half) + 4 * (c >= half);
              f[octant] += 8.0 / (n * n * n);
            }
          }
        }
      }
    }
  }
  return fractions;
}

std::vector<dc::OctantFractions> bruteForceFractions(const dc::TriangleMesh& surface,
                                                     const dc::VoxelGrid& grid, int levels,
                                                     bool every_part) {
  const dc::InsideTest exact = [&surface](const Eigen::Vector3d& q) {
    return dc::exactWindingNumber(surface, q) >= 0.5;
  };
  return bruteForceFractions(surface, grid, levels, every_part, exact);
}

// Every cell of the voxelization holds the reference's fractions, and every cell it leaves out
// holds nothing in the reference.
void expectReferenceFractions(const dc::TriangleMesh& surface, double cell_size, int levels,
                              bool every_part = true) {
  dc::VoxelSettings settings;
  settings.cell_size = cell_size;
  const dc::VoxelGrid grid = dc::voxelGridFor(surface, settings);
  const dc::Voxelization voxels = dc::voxelize(surface, grid, levels);
  const std::vector<dc::OctantFractions> reference =
      bruteForceFractions(surface, grid, levels, every_part);
  int compared = 0;
  for (long index = 0; index < grid.numCells(); ++index) {
    const int cell = voxels.cell_at[index];
    for (int o = 0; o < 8; ++o) {
      const double got = cell < 0 ? 0.0 : voxels.mesh.cell_fractions[cell][o];
      EXPECT_NEAR(got, reference[index][o], 1e-12) << "grid cell " << index << " octant " << o;
    }
    compared += cell >= 0;
  }
  EXPECT_GT(compared, 0);
}

dc::TriangleMesh withoutCap(const dc::TriangleMesh& closed, double z) {
  dc::TriangleMesh open = closed;
  open.triangles.clear();
  for (const Eigen::Vector3i& t : closed.triangles) {
    if (closed.vertices[t[0]].z() < z || closed.vertices[t[1]].z() < z) open.triangles.push_back(t);
  }
  return open;
}

}  // namespace

TEST(VoxelizationReference, ClosedShapesGiveTheExactWindingNumbersFractions) {
  expectReferenceFractions(dt::sphereSurface(0.1, Eigen::Vector3d(0.01, 0.02, -0.03), 12, 24), 0.04,
                           3);
  expectReferenceFractions(dt::torusSurface(0.1, 0.04, 24, 12), 0.03, 2);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.rotate(Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 3).normalized()));
  pose.pretranslate(Eigen::Vector3d(0.013, -0.007, 0.021));
  expectReferenceFractions(
      dt::boxSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(0.1), pose), 0.025, 3);
  // An aligned box: triangles on the grid's planes and rays along their edges.
  expectReferenceFractions(
      dt::boxSurface(Eigen::Vector3d(-0.1, 0.2, 0.0), Eigen::Vector3d(0.5, 0.4, 0.1)), 0.05, 2);
}

TEST(VoxelizationReference, SelfIntersectingAndOpenShapesToo) {
  // Two spheres overlapping, one soup: winding number 2 in the lens, inside once.
  dc::TriangleMesh both = dt::sphereSurface(0.1, Eigen::Vector3d::Zero(), 12, 24);
  const dc::TriangleMesh other = dt::sphereSurface(0.1, Eigen::Vector3d(0.1, 0, 0), 12, 24);
  const int offset = static_cast<int>(both.vertices.size());
  both.vertices.insert(both.vertices.end(), other.vertices.begin(), other.vertices.end());
  for (const Eigen::Vector3i& t : other.triangles) both.triangles.push_back(t.array() + offset);
  ASSERT_TRUE(dc::isClosedSurface(both));
  expectReferenceFractions(both, 0.04, 2);
  // A sphere with its cap above z = 0.8 r cut away: the caps over the hole make up the count.
  const dc::TriangleMesh open =
      withoutCap(dt::sphereSurface(0.1, Eigen::Vector3d::Zero(), 12, 24), 0.08);
  ASSERT_FALSE(dc::isClosedSurface(open));
  EXPECT_FALSE(dc::holeCaps(open).triangles.empty());
  expectReferenceFractions(open, 0.04, 2, false);
}

TEST(RayWinding, APointOnAnAlignedFaceIsOnTheSameSideInEveryRow) {
  // Box a, [0, 1]^3, and box b, [2, 3] x [0, 0.5] x [0, 1]: rows through b walk from a's face at
  // x = 1 towards -x (fewer triangles that way), rows above it towards +x.
  dc::TriangleMesh two = dt::boxSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
  const dc::TriangleMesh b = dt::boxSurface(Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(3, 0.5, 1));
  for (const Eigen::Vector3i& t : b.triangles) two.triangles.push_back(t.array() + 8);
  two.vertices.insert(two.vertices.end(), b.vertices.begin(), b.vertices.end());
  dc::VoxelGrid grid;  // no face of the boxes on a face between cells
  grid.origin = Eigen::Vector3d::Constant(-0.1);
  grid.cell_size = 0.4;
  grid.cells = Eigen::Vector3i(8, 3, 3);
  const dc::RayWinding rays(two, grid);
  // On a face, a point is where it is moved a little towards -x: inside at a's face x = 1 and
  // b's x = 3, outside at x = 0 and x = 2.
  for (double y : {0.05, 0.2, 0.45, 0.6, 0.8, 0.95}) {
    for (double z : {0.1, 0.45, 0.9}) {
      EXPECT_EQ(rays.at({1.0, y, z}), 1) << "y " << y << " z " << z;
      EXPECT_EQ(rays.at({0.0, y, z}), 0) << "y " << y << " z " << z;
      if (y > 0.5) continue;
      EXPECT_EQ(rays.at({3.0, y, z}), 1) << "y " << y << " z " << z;
      EXPECT_EQ(rays.at({2.0, y, z}), 0) << "y " << y << " z " << z;
    }
  }
}

TEST(VoxelizationReference, HoleCapsCloseTheSurface) {
  const dc::TriangleMesh open =
      withoutCap(dt::torusSurface(0.1, 0.04, 24, 12), std::numeric_limits<double>::infinity());
  ASSERT_TRUE(dc::isClosedSurface(open));  // nothing cut: closed, no cap
  EXPECT_TRUE(dc::holeCaps(open).triangles.empty());
  dc::TriangleMesh cut = withoutCap(dt::sphereSurface(0.1, Eigen::Vector3d::Zero(), 12, 24), 0.05);
  // And a second hole at the south pole.
  cut.triangles.erase(cut.triangles.begin());
  const dc::TriangleMesh caps = dc::holeCaps(cut);
  EXPECT_EQ(caps.vertices.size(), cut.vertices.size() + 2);  // an apex per hole
  dc::TriangleMesh closed = cut;
  closed.vertices = caps.vertices;
  closed.triangles.insert(closed.triangles.end(), caps.triangles.begin(), caps.triangles.end());
  EXPECT_TRUE(dc::isClosedSurface(closed));
}

TEST(VoxelGrid, TooManyCellsAreRefusedSayingHowManyHowMuchMemoryAndWhichKey) {
  const dc::TriangleMesh box =
      dt::boxSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d(1.0, 0.5, 0.25));
  dc::VoxelSettings settings;
  settings.cell_size = 0.001;  // 1000 x 500 x 250 cells
  try {
    dc::voxelGridFor(box, settings);
    FAIL() << "125 million cells accepted";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("1000 x 500 x 250 = 125000000 cells"), std::string::npos) << message;
    EXPECT_NE(message.find("more than max_cells (1000000)"), std::string::npos) << message;
    EXPECT_NE(message.find("37.5 GB"), std::string::npos) << message;  // voxelizing them
    EXPECT_NE(message.find("1.5 TB"), std::string::npos) << message;   // a body of them
    EXPECT_NE(message.find("raise max_cells"), std::string::npos) << message;
  }
  // Raised, the same grid is sized (voxelGridFor allocates nothing for it).
  settings.max_cells = 200000000;
  EXPECT_EQ(dc::voxelGridFor(box, settings).numCells(), 125000000);
  // And lowered, a small one is refused.
  settings.cell_size = 0.1;
  settings.max_cells = 10;
  EXPECT_THROW(dc::voxelGridFor(box, settings), std::invalid_argument);
  // A cell size that makes more cells than a double counts exactly still says how many.
  settings.cell_size = 1e-300;
  settings.max_cells = dc::kMaxBoxMeshCells;
  try {
    dc::voxelGridFor(box, settings);
    FAIL() << "an endless grid accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("more than max_cells"), std::string::npos) << e.what();
  }
}

TEST(VoxelGrid, AGridIntIndicesCannotNumberIsRefusedWhateverMaxCellsSays) {
  dc::VoxelSettings settings;
  settings.cell_size = 1.0;
  settings.max_cells = std::numeric_limits<long>::max();
  // 3e9 cells along x, one along y and z: an axis past INT_MAX.
  const dc::TriangleMesh rod = dt::boxSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d(3e9, 1, 1));
  try {
    dc::voxelGridFor(rod, settings);
    FAIL() << "3e9 cells along a side accepted";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("3000000000 x 1 x 1 cells"), std::string::npos) << message;
    EXPECT_NE(message.find("more than a mesh can number (2147483647"), std::string::npos)
        << message;
  }
  // At the most max_cells may be, the error does not ask to raise it.
  settings.max_cells = dc::kMostGridCells;
  try {
    dc::voxelGridFor(rod, settings);
    FAIL() << "3e9 cells accepted under max_cells " << settings.max_cells;
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("more than max_cells (2147483647)"), std::string::npos) << message;
    EXPECT_EQ(message.find("raise max_cells"), std::string::npos) << message;
  }
  // 1290^3 cells are fewer than INT_MAX, their 1291^3 nodes are not.
  const dc::TriangleMesh cube =
      dt::boxSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(1290.0));
  EXPECT_THROW(dc::voxelGridFor(cube, settings), std::invalid_argument);
  // One cell fewer along a side: 1289^3 cells, 1290^3 nodes, both numbered.
  const dc::TriangleMesh smaller =
      dt::boxSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(1289.0));
  EXPECT_EQ(dc::voxelGridFor(smaller, settings).cells, Eigen::Vector3i::Constant(1289));
}

TEST(VoxelGrid, ACoordinateThatIsNotFiniteIsNamedNotCountedInCells) {
  for (double bad :
       {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
        std::numeric_limits<double>::quiet_NaN()}) {
    dc::TriangleMesh box = dt::boxSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
    box.vertices[5].y() = bad;
    dc::VoxelSettings settings;
    settings.cell_size = 0.1;
    try {
      dc::voxelGridFor(box, settings);
      FAIL() << bad << " accepted";
    } catch (const std::invalid_argument& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("not finite"), std::string::npos) << message;
      EXPECT_NE(message.find("vertex 6"), std::string::npos) << message;  // numbered from 1
      EXPECT_EQ(message.find("cells"), std::string::npos) << message;
    }
  }
}

TEST(VoxelGrid, CellsTooLargeForThePartSaySoAndGiveItsSize) {
  const dc::TriangleMesh box =
      dt::boxSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.04, 0.02, 0.01));
  dc::VoxelSettings settings;
  settings.cell_size = 10.0;
  try {
    dc::voxelize(box, dc::voxelGridFor(box, settings), settings.levels);
    FAIL() << "a part of 4 cm in a cell of 10 m";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("cell size 10 m is too large for the part, 0.04 x 0.02 x 0.01 m"),
              std::string::npos)
        << message;
    EXPECT_EQ(message.find("open, or a sheet"), std::string::npos) << message;
  }
}

TEST(Voxelization, ProgressRunsFromNoneToEveryCellNeverBack) {
  const dc::TriangleMesh torus = dt::torusSurface(0.1, 0.04, 24, 12);
  dc::VoxelSettings settings;
  settings.cell_size = 0.02;
  const dc::VoxelGrid grid = dc::voxelGridFor(torus, settings);
  std::vector<long> done;
  const dc::Voxelization voxels =
      dc::voxelize(torus, grid, settings.levels, [&](long cells, long total) {
        EXPECT_EQ(total, grid.numCells());
        done.push_back(cells);
      });
  ASSERT_GE(done.size(), 3u);
  EXPECT_EQ(done.front(), 0);
  EXPECT_EQ(done.back(), grid.numCells());
  for (size_t k = 1; k < done.size(); ++k) EXPECT_GE(done[k], done[k - 1]) << k;
  // The same cells as without a progress report.
  EXPECT_EQ(voxels.mesh.cell_fractions,
            dc::voxelize(torus, grid, settings.levels).mesh.cell_fractions);
}

TEST(VoxelizationReference, FacesARoundingOutsideTheGridStillCount) {
  // Two boxes with an STL's single-precision corners (0.1f, 0.3f, 0.4f): the grid, centred on
  // them, leaves the faces at x = 0 a rounding outside it.
  dc::TriangleMesh two = dt::boxSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.1f, 0.1f, 0.1f));
  const dc::TriangleMesh other =
      dt::boxSurface(Eigen::Vector3d(0.3f, 0.0, 0.0), Eigen::Vector3d(0.4f, 0.1f, 0.1f));
  for (const Eigen::Vector3i& t : other.triangles) two.triangles.push_back(t.array() + 8);
  two.vertices.insert(two.vertices.end(), other.vertices.begin(), other.vertices.end());
  expectReferenceFractions(two, 0.05, 2);
  dc::VoxelSettings settings;
  settings.cell_size = 0.05;
  EXPECT_EQ(dc::voxelize(two, dc::voxelGridFor(two, settings), 3).mesh.cells.size(), 16u);
}

TEST(VoxelizationReference, ASurfaceFacingEveryWhichWayIsAskedByTheTree) {
  // A closed ball inside a shell of which every other triangle is turned inside out: open edges
  // everywhere, caps that would cross the whole grid. It is asked by the generalized winding
  // number's tree, which finds the ball (the shell's turned halves all but cancel).
  dc::TriangleMesh mixed = dt::sphereSurface(0.12, Eigen::Vector3d::Zero(), 8, 16);
  for (size_t t = 0; t < mixed.triangles.size(); t += 2) {
    std::swap(mixed.triangles[t][1], mixed.triangles[t][2]);
  }
  EXPECT_GT(dc::holeCaps(mixed).triangles.size(), mixed.triangles.size() / 2);
  const dc::TriangleMesh ball = dt::sphereSurface(0.1, Eigen::Vector3d::Zero(), 12, 24);
  const int offset = static_cast<int>(mixed.vertices.size());
  mixed.vertices.insert(mixed.vertices.end(), ball.vertices.begin(), ball.vertices.end());
  for (const Eigen::Vector3i& t : ball.triangles) mixed.triangles.push_back(t.array() + offset);
  dc::VoxelSettings settings;
  settings.cell_size = 0.04;
  const dc::VoxelGrid grid = dc::voxelGridFor(mixed, settings);
  EXPECT_FALSE(dc::GridInside(mixed, grid).countsRays());
  const dc::WindingNumber tree(mixed);
  const std::vector<dc::OctantFractions> reference = bruteForceFractions(
      mixed, grid, 2, false, [&tree](const Eigen::Vector3d& q) { return tree.at(q) >= 0.5; });
  dc::Voxelization voxels;
  ASSERT_NO_THROW(voxels = dc::voxelize(mixed, grid, 2));
  EXPECT_GT(voxels.mesh.cells.size(), 8u);
  for (long index = 0; index < grid.numCells(); ++index) {
    const int cell = voxels.cell_at[index];
    for (int o = 0; o < 8; ++o) {
      EXPECT_EQ(cell < 0 ? 0.0 : voxels.mesh.cell_fractions[cell][o], reference[index][o]);
    }
  }
}

TEST(VoxelizationReference, LargeTrianglesSlantingAcrossAFineGridAreAskedByTheTree) {
  // A long rod turned towards the diagonal: the box of each sliver down its side fills much of
  // the grid, so binning them for the rays would store about the triangles times the cells.
  dc::TriangleMesh rod = dt::cylinderSurface(0.02, 0.3, 64);
  const Eigen::Quaterniond turn =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Ones());
  for (Eigen::Vector3d& v : rod.vertices) v = turn * v;
  dc::VoxelSettings settings;
  settings.cell_size = 0.0125;
  const dc::VoxelGrid grid = dc::voxelGridFor(rod, settings);
  const double items = static_cast<double>(rod.triangles.size() + grid.numCells());
  EXPECT_GT(dc::rayBinEntries(rod, grid), 16.0 * items);
  EXPECT_FALSE(dc::GridInside(rod, grid).countsRays());
  expectReferenceFractions(rod, settings.cell_size, 2, false);
  // A closed ball's few entries per cell keep the rays.
  const dc::TriangleMesh ball = dt::sphereSurface(0.1, Eigen::Vector3d::Zero(), 12, 24);
  EXPECT_TRUE(dc::GridInside(ball, dc::voxelGridFor(ball, settings)).countsRays());
}

TEST(VoxelizationReference, ManySmallHolesGiveTheExactWindingNumbersFractions) {
  // Every ninth triangle of a ball taken away: a couple of hundred holes, each capped.
  const dc::TriangleMesh ball = dt::sphereSurface(0.1, Eigen::Vector3d::Zero(), 24, 48);
  dc::TriangleMesh holey = ball;
  holey.triangles.clear();
  for (size_t t = 0; t < ball.triangles.size(); ++t) {
    if (t % 9 != 4) holey.triangles.push_back(ball.triangles[t]);
  }
  const dc::TriangleMesh caps = dc::holeCaps(holey);
  EXPECT_GT(caps.vertices.size(), holey.vertices.size() + 100);  // an apex per hole
  dc::VoxelSettings settings;
  settings.cell_size = 0.04;
  EXPECT_TRUE(dc::GridInside(holey, dc::voxelGridFor(holey, settings)).countsRays());
  expectReferenceFractions(holey, settings.cell_size, 2, false);
}
