// The check of a surface before it is voxelized: each kind of messy input is counted (and
// repaired where the winding number would be misled), and the warnings give the counts.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <limits>
#include <string>

#include "awkward_surfaces.h"
#include "deformable_sim/core/bodies/mass_properties.h"
#include "deformable_sim/core/geometry/self_crossings.h"
#include "deformable_sim/core/geometry/triangles_cross.h"
#include "deformable_sim/core/surface_bodies/surface_body.h"
#include "deformable_sim/core/surface_bodies/surface_check.h"
#include "deformable_sim/core/surface_bodies/voxelization.h"
#include "surface_test_helpers.h"

namespace dc = deformable_sim::core;
namespace dt = deformable_sim::test;

namespace {

constexpr double kDensity = 1000.0;  // kg/m^3

using Strings = std::vector<std::string>;

dc::TriangleMesh ball(double radius, const Eigen::Vector3d& centre = Eigen::Vector3d::Zero()) {
  return dt::sphereSurface(radius, centre, 16, 32);
}

// `b`'s triangles and vertices appended to `a`'s.
dc::TriangleMesh joined(dc::TriangleMesh a, const dc::TriangleMesh& b) {
  const int offset = static_cast<int>(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (const Eigen::Vector3i& t : b.triangles) a.triangles.push_back(t.array() + offset);
  return a;
}

dc::TriangleMesh turned(dc::TriangleMesh mesh) {
  for (Eigen::Vector3i& t : mesh.triangles) std::swap(t[1], t[2]);
  return mesh;
}

// The body's mass of `surface` voxelized at `cell_size`, with the warnings it gave.
double massOf(const dc::TriangleMesh& surface, double cell_size, Strings* warnings) {
  dc::VoxelSettings settings;
  settings.cell_size = cell_size;
  return dc::massProperties(dc::bodyFromSurface(surface, settings, warnings).voxels.mesh, kDensity)
      .mass;
}

const std::string kHoles =
    " (the surface has holes; inside is judged by the winding number, volume may be off)";

}  // namespace

TEST(SurfaceCheck, AClosedSurfaceHasNothingToReport) {
  dc::TriangleMesh sphere = ball(0.1);
  const dc::TriangleMesh before = sphere;
  const dc::SurfaceCheck check = dc::checkSurface(sphere);
  EXPECT_EQ(check.shells, 1);
  EXPECT_EQ(check.open_edges + check.overused_edges + check.misoriented, 0);
  EXPECT_EQ(check.zero_area + check.duplicates + check.crossings.pairs, 0);
  EXPECT_FALSE(check.inside_out);
  EXPECT_TRUE(dc::surfaceWarnings(check).empty());
  EXPECT_EQ(sphere.triangles, before.triangles);
  EXPECT_EQ(sphere.vertices, before.vertices);
}

TEST(SurfaceCheck, ZeroAreaAndRepeatedTrianglesAreDroppedAndCounted) {
  dc::TriangleMesh sphere = ball(0.1);
  const int triangles = static_cast<int>(sphere.triangles.size());
  // Three triangles with their corners on a line (two on a mesh edge, one at its middle).
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3i t = sphere.triangles[10 * k];
    sphere.vertices.push_back(0.5 * (sphere.vertices[t[0]] + sphere.vertices[t[1]]));
    sphere.triangles.emplace_back(t[0], t[1], static_cast<int>(sphere.vertices.size()) - 1);
  }
  // Triangle 0 three times more, triangle 1 once more: four repeats.
  for (int k = 0; k < 3; ++k) sphere.triangles.push_back(sphere.triangles[0]);
  sphere.triangles.push_back(sphere.triangles[1]);
  const int vertices = static_cast<int>(sphere.vertices.size());
  const dc::SurfaceCheck check = dc::checkSurface(sphere, 2);  // and 2 the reader dropped
  EXPECT_EQ(check.zero_area, 5);
  EXPECT_EQ(check.duplicates, 4);
  EXPECT_EQ(check.open_edges, 0);  // the zero-area triangles went first
  EXPECT_EQ(static_cast<int>(sphere.triangles.size()), triangles);
  EXPECT_EQ(static_cast<int>(sphere.vertices.size()), vertices - 3);  // the middles unused
  EXPECT_EQ(dc::surfaceWarnings(check),
            Strings{"9 triangles dropped: 5 with zero area, 4 duplicates"});
}

TEST(SurfaceCheck, ATriangleAndItsTurnedCopyCancel) {
  dc::TriangleMesh box = dc::boxSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
  const Eigen::Vector3i t = box.triangles[0];
  box.triangles.emplace_back(t[0], t[2], t[1]);
  const dc::SurfaceCheck check = dc::checkSurface(box);
  EXPECT_EQ(check.duplicates, 2);
  EXPECT_EQ(check.open_edges, 3);  // where the pair was
  EXPECT_EQ(box.triangles.size(), 11u);
  EXPECT_EQ(dc::surfaceWarnings(check),
            (Strings{"2 triangles dropped: 2 duplicates", "3 open edges" + kHoles}));
}

TEST(SurfaceCheck, OpenEdgesAreCountedAndTheVolumeStaysNearlyRight) {
  // The measured case: a box missing two triangles (one face) gave 12 % too much, silently.
  dc::TriangleMesh box = dc::boxSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(0.1));
  dc::TriangleMesh open = box;
  open.triangles.erase(open.triangles.begin(), open.triangles.begin() + 2);
  Strings warnings;
  const double mass = massOf(open, 0.01, &warnings);
  ASSERT_FALSE(warnings.empty());
  EXPECT_EQ(warnings[0], "4 open edges" + kHoles);
  // The winding number bridges the missing face: the whole box, to the sampling.
  EXPECT_NEAR(mass / (kDensity * 1e-3), 1.0, 0.005);
  dc::TriangleMesh one_hole = ball(0.1);
  one_hole.triangles.erase(one_hole.triangles.begin() + 40);
  EXPECT_EQ(dc::checkSurface(one_hole).open_edges, 3);
}

TEST(SurfaceCheck, AnEdgeOfThreeTrianglesIsCounted) {
  dc::TriangleMesh box = dc::boxSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
  // A fin on the edge between triangle 0's first two corners.
  const Eigen::Vector3i t = box.triangles[0];
  box.vertices.emplace_back(-1.0, -1.0, -1.0);
  box.triangles.emplace_back(t[0], t[1], 8);
  const dc::SurfaceCheck check = dc::checkSurface(box);
  EXPECT_EQ(check.overused_edges, 1);
  EXPECT_EQ(check.open_edges, 2);
  EXPECT_EQ(check.shells, 1);
  EXPECT_EQ(dc::surfaceWarnings(check)[1],
            "1 edge shared by more than two triangles (inside is judged by the winding number, "
            "volume may be off)");
}

TEST(SurfaceCheck, TrianglesFacingAgainstTheirNeighboursAreTurned) {
  dc::TriangleMesh sphere = ball(0.1);
  const dc::TriangleMesh right = sphere;
  for (int t : {3, 50, 200, 401, 777}) std::swap(sphere.triangles[t][0], sphere.triangles[t][1]);
  const dc::SurfaceCheck check = dc::checkSurface(sphere);
  EXPECT_EQ(check.misoriented, 5);
  EXPECT_EQ(check.open_edges, 0);
  EXPECT_FALSE(check.inside_out);
  EXPECT_NEAR(dc::enclosedVolume(sphere), dc::enclosedVolume(right), 1e-15);
  EXPECT_EQ(dc::surfaceWarnings(check),
            Strings{"5 triangles faced against their neighbours and turned to agree with them"});
}

TEST(SurfaceCheck, AnOpenSurfaceFacingOutwardsIsNotTurnedWhereverItsFirstVertexIs) {
  // A wide, flat box open at its bottom with a tall stem on it, the stem's vertices first: about
  // the stem's top, the open box's triangles sum to a negative volume (64 - 64 x 16 / 3 cm^3).
  dc::TriangleMesh base =
      dt::boxSurface(Eigen::Vector3d(-0.04, -0.04, 0.0), Eigen::Vector3d(0.04, 0.04, 0.01));
  std::vector<Eigen::Vector3i> sides_and_top;
  for (const Eigen::Vector3i& t : base.triangles) {
    double z = 0.0;
    for (int c = 0; c < 3; ++c) z = std::max(z, base.vertices[t[c]].z());
    if (z > 0.0) sides_and_top.push_back(t);
  }
  ASSERT_EQ(sides_and_top.size(), base.triangles.size() - 2);
  base.triangles = sides_and_top;
  dc::TriangleMesh cup = dt::joined(dt::boxSurface(Eigen::Vector3d(-0.0025, -0.0025, 0.01),
                                                   Eigen::Vector3d(0.0025, 0.0025, 0.16)),
                                    base);
  // Vertex 7 is the stem's top corner: make it the first.
  std::swap(cup.vertices[0], cup.vertices[7]);
  for (Eigen::Vector3i& t : cup.triangles) {
    for (int c = 0; c < 3; ++c) t[c] = t[c] == 0 ? 7 : t[c] == 7 ? 0 : t[c];
  }
  ASSERT_GT(cup.vertices.front().z(), 0.15);
  const dc::TriangleMesh before = cup;
  const dc::SurfaceCheck check = dc::checkSurface(cup);
  EXPECT_FALSE(check.inside_out);
  EXPECT_EQ(check.open_edges, 4);
  EXPECT_EQ(cup.triangles, before.triangles);
}

TEST(SurfaceCheck, AnInsideOutSurfaceIsTurned) {
  const dc::TriangleMesh sphere = ball(0.1);
  Strings right_warnings, warnings;
  const double right = massOf(sphere, 0.02, &right_warnings);
  EXPECT_DOUBLE_EQ(massOf(turned(sphere), 0.02, &warnings), right);
  EXPECT_EQ(warnings,
            Strings{"the surface faced inwards (it enclosed a negative volume) and was turned "
                    "outwards"});
  // Mostly turned: the few the right way round are the ones against their neighbours.
  dc::TriangleMesh mostly = turned(sphere);
  std::swap(mostly.triangles[7][1], mostly.triangles[7][2]);
  const dc::SurfaceCheck check = dc::checkSurface(mostly);
  EXPECT_EQ(check.misoriented, 1);
  EXPECT_TRUE(check.inside_out);
  EXPECT_NEAR(dc::enclosedVolume(mostly), dc::enclosedVolume(sphere), 1e-15);
}

TEST(SurfaceCheck, AShellFacingInwardsInsideAnotherIsAVoid) {
  const dc::TriangleMesh outer = dt::sphereSurface(0.1, Eigen::Vector3d::Zero(), 32, 64);
  const dc::TriangleMesh inner = dt::sphereSurface(0.05, Eigen::Vector3d(0.02, 0, 0), 32, 64);
  const double expected =
      kDensity * (dc::enclosedVolume(outer) - dc::enclosedVolume(inner));  // polygons' volumes
  Strings warnings;
  EXPECT_NEAR(massOf(joined(outer, turned(inner)), 0.02, &warnings) / expected, 1.0, 0.005);
  EXPECT_EQ(warnings, Strings{"2 shells (separate surfaces: 1 void inside another shell)"});
  // Both the wrong way round: turned as a whole, the void stays a void.
  warnings.clear();
  EXPECT_NEAR(massOf(joined(turned(outer), inner), 0.02, &warnings) / expected, 1.0, 0.005);
  EXPECT_EQ(warnings,
            (Strings{"the surface faced inwards (it enclosed a negative volume) and was turned "
                     "outwards",
                     "2 shells (separate surfaces: 1 void inside another shell)"}));
}

TEST(SurfaceCheck, AShellFacingInwardsAloneIsTurned) {
  const dc::TriangleMesh big = ball(0.1);
  const dc::TriangleMesh small = ball(0.05, Eigen::Vector3d(0.3, 0, 0));
  dc::TriangleMesh both = joined(big, turned(small));
  const dc::SurfaceCheck check = dc::checkSurface(both);
  EXPECT_FALSE(check.inside_out);
  EXPECT_EQ(check.shells, 2);
  EXPECT_EQ(check.turned_shells, 1);
  EXPECT_EQ(check.voids, 0);
  EXPECT_NEAR(dc::enclosedVolume(both), dc::enclosedVolume(big) + dc::enclosedVolume(small), 1e-12);
  EXPECT_EQ(dc::surfaceWarnings(check),
            Strings{"2 shells (separate surfaces: 1 facing inwards alone, turned outwards)"});
}

TEST(TrianglesCross, ThroughButNotTouchingOrInOnePlane) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  // Through: a triangle standing across the first one.
  EXPECT_TRUE(dc::trianglesCross(a, b, c, {0.2, 0.2, -1}, {0.2, 0.2, 1}, {0.3, -1, 0}));
  // Beside it, above it, touching it with a corner, lying in its plane.
  EXPECT_FALSE(dc::trianglesCross(a, b, c, {2, 2, -1}, {2, 2, 1}, {3, 1, 0}));
  EXPECT_FALSE(dc::trianglesCross(a, b, c, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}));
  EXPECT_FALSE(dc::trianglesCross(a, b, c, {0.2, 0.2, 0}, {0.2, 0.2, 1}, {0.3, 0.5, 1}));
  EXPECT_FALSE(dc::trianglesCross(a, b, c, {0.1, 0.1, 0}, {2, 0.1, 0}, {0.1, 2, 0}));
}

TEST(SurfaceCheck, TrianglesThatCrossAreCounted) {
  // A large triangle through the middle of a box crosses both triangles of each of its four
  // sides, and is an open shell of its own.
  dc::TriangleMesh mesh = dc::boxSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
  mesh.vertices.insert(mesh.vertices.end(), {{-1, -1, 0.5}, {4, -1, 0.5}, {-1, 4, 0.5}});
  mesh.triangles.emplace_back(8, 9, 10);
  const dc::SurfaceCheck check = dc::checkSurface(mesh);
  EXPECT_EQ(check.crossings.pairs, 8);
  EXPECT_TRUE(check.crossings.complete);
  EXPECT_EQ(check.shells, 2);
  EXPECT_EQ(check.open_edges, 3);
  EXPECT_EQ(dc::surfaceWarnings(check).back(),
            "8 pairs of triangles cross (the surface passes through itself; inside is judged by "
            "the winding number, so parts that overlap count once)");
  // A budget of one test per triangle stops early, and says so.
  const dc::SelfCrossings some = dc::selfCrossings(mesh, 1);
  EXPECT_FALSE(some.complete);
  EXPECT_LE(some.pairs, 8);
}

TEST(SurfaceCheck, SeventyThousandCleanTrianglesShowNoProblem) {
  // What it costs: deformable_sim_perf --benchmark_filter=CheckScan.
  dc::TriangleMesh scan = dt::sphereSurface(0.1, Eigen::Vector3d::Zero(), 150, 234);
  ASSERT_GT(scan.triangles.size(), 69000u);
  const dc::SurfaceCheck check = dc::checkSurface(scan);
  EXPECT_EQ(check.crossings.pairs, 0);
  EXPECT_TRUE(check.crossings.complete);
  EXPECT_EQ(check.open_edges, 0);
  EXPECT_EQ(check.zero_area + check.duplicates + check.misoriented, 0);
  EXPECT_TRUE(dc::surfaceWarnings(check).empty());
}

TEST(SurfaceCheck, ABodyFromASurfaceWithAnInfiniteCornerNamesItNotZeroAreaTriangles) {
  dc::TriangleMesh sphere = ball(0.1);
  sphere.vertices[3].x() = std::numeric_limits<double>::infinity();
  dc::VoxelSettings settings;
  settings.cell_size = 0.02;
  try {
    dc::bodyFromSurface(sphere, settings, nullptr);
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("not finite"), std::string::npos) << message;
    EXPECT_NE(message.find("vertex 4 "), std::string::npos) << message;
    EXPECT_EQ(message.find("zero area"), std::string::npos) << message;
  }
}
