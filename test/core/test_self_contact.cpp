// A body touching itself (the `self` key of the contact effect): a thin strip folded over and
// pressed flat onto itself, and a U whose arms are pushed into each other (also one made from its
// surface). Each is checked with a measure of its own (winding numbers and distances, brute
// force) and against the same scene without self-contact, in which the body does pass through
// itself.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <functional>

#include "contact_test_helpers.h"
#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/selection.h"
#include "deformable_sim/core/session/simulation.h"
#include "deformable_sim/core/surface_bodies/surface_body.h"
#include "scene_builder.h"
#include "simulation_test_helpers.h"
#include "surface_test_helpers.h"

namespace dc = deformable_sim::core;
using deformable_sim::test::boxSelection;
using deformable_sim::test::distanceToTriangle;
using deformable_sim::test::windingNumber;

namespace {

/// Points spread over each surface triangle (corners, edges and inside): parts of a body can
/// cross each other between its nodes (two arms crossing like an X), which the nodes alone miss.
constexpr int kSampleDivisions = 4;

/// How deep any point of a closed surface (corners at `x`, at rest at `rest`; or a body's) is
/// inside its own volume, m. Each point is taken a hair inside its own triangle (on the surface
/// its winding number is ill-defined): there it winds once, and twice when it is also inside
/// another part of the body. Its depth is the distance to the nearest triangle whose corners were
/// all more than `away` from it at rest: another part's, not its own neighbourhood's.
double deepestInsideItself(const std::vector<dc::Triangle>& triangles, const Eigen::VectorXd& x,
                           const Eigen::VectorXd& rest, double away) {
  const auto at = [](const Eigen::VectorXd& v, const dc::Triangle& t, const Eigen::Vector3d& w) {
    return Eigen::Vector3d(w[0] * v.segment<3>(3 * t[0]) + w[1] * v.segment<3>(3 * t[1]) +
                           w[2] * v.segment<3>(3 * t[2]));
  };
  double deepest = 0.0;
  for (const dc::Triangle& sampled : triangles) {
    for (int i = 0; i <= kSampleDivisions; ++i) {
      for (int j = 0; i + j <= kSampleDivisions; ++j) {
        const Eigen::Vector3d w =
            Eigen::Vector3d(i, j, kSampleDivisions - i - j) / double(kSampleDivisions);
        const Eigen::Vector3d p = at(x, sampled, w), p0 = at(rest, sampled, w);
        const Eigen::Vector3d a = x.segment<3>(3 * sampled[0]), b = x.segment<3>(3 * sampled[1]),
                              c = x.segment<3>(3 * sampled[2]);
        const Eigen::Vector3d inward = -1e-9 * (b - a).cross(c - a).normalized();
        if (windingNumber(p + inward, x, triangles) < 1.5) continue;
        double distance = std::numeric_limits<double>::infinity();
        for (const dc::Triangle& t : triangles) {
          bool far = true;
          for (int k = 0; k < 3; ++k) far = far && (rest.segment<3>(3 * t[k]) - p0).norm() > away;
          if (!far) continue;
          distance = std::min(distance,
                              distanceToTriangle(p, x.segment<3>(3 * t[0]), x.segment<3>(3 * t[1]),
                                                 x.segment<3>(3 * t[2])));
        }
        deepest = std::max(deepest, distance);
      }
    }
  }
  return deepest;
}

double deepestInsideItself(const dc::Body& body, double away) {
  return deepestInsideItself(dc::extractSurface(body.mesh()), body.positions(),
                             body.restPositions(), away);
}

/// The hexahedra of a box mesh whose centres `keep` accepts, with the nodes they use.
dc::Mesh keptCells(const dc::Mesh& box, const std::function<bool(const Eigen::Vector3d&)>& keep) {
  dc::Mesh mesh;
  std::vector<int> index(box.numNodes(), -1);
  for (const dc::Cell& cell : box.cells) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int k = 0; k < 8; ++k) centre += box.positions[cell.nodes[k]] / 8.0;
    if (!keep(centre)) continue;
    dc::Cell kept = cell;
    for (int k = 0; k < 8; ++k) {
      int& i = index[cell.nodes[k]];
      if (i < 0) {
        i = mesh.numNodes();
        mesh.positions.push_back(box.positions[cell.nodes[k]]);
        mesh.node_numbers.push_back(i + 1);
      }
      kept.nodes[k] = i;
    }
    mesh.cells.push_back(kept);
  }
  mesh.incompatible_modes = true;  // one cell through: plain hexahedra would lock in bending
  return mesh;
}

dc::SceneSpec selfContactScene(bool self) {
  dc::SceneSpec spec = deformable_sim::test::SceneBuilder()
                           .dt(0.01)
                           .warped()
                           .damping(2.0, 0.005)
                           .contact(0.3, false, self);
  dc::BodySpec body;
  body.name = "body";
  body.material = {1.0e5, 0.3, 100.0};
  spec.bodies.push_back(body);
  return spec;
}

/// The depth a body may be left inside itself: 1 % of the diagonal of its rest bounding box.
double toleranceOf(const dc::Body& body) {
  const auto rest = body.restPositions().reshaped(3, body.numNodes());
  return 0.01 * (rest.rowwise().maxCoeff() - rest.rowwise().minCoeff()).norm();
}

struct SelfContactRun {
  double deepest = 0.0;    ///< m, the deepest inside itself over the run
  double tolerance = 0.0;  ///< m, toleranceOf the body
  long self_contacts = 0;
  int inverted = 0;  ///< elements inverted at the end
  bool finite = false;
};

// --- A U whose arms are pushed into each other --------------------------------------------------

/// The U: a 0.3 m square, 5 cm deep, of 5 cm cells; its base 5 cm high, its arms 5 cm wide.
dc::Mesh uMesh() {
  const dc::Mesh box =
      dc::makeBoxMesh({0, 0, 0}, {0.3, 0.05, 0.3}, {6, 1, 6}, dc::BoxElement::kHexahedron);
  return keptCells(
      box, [](const Eigen::Vector3d& c) { return c.z() < 0.05 || c.x() < 0.05 || c.x() > 0.25; });
}

struct UEnd {
  SelfContactRun run;
  double left_tip = 0.0, right_tip = 0.0;  ///< m, the mean x of each arm's top face
};

/// Step s of pushing the tops of a U's arms (`left`, `right`) towards each other with 2 N each,
/// ramped up over the first second.
void pushTips(dc::Body& body, const std::vector<int>& left, const std::vector<int>& right, int s) {
  const double force = 2.0 * std::min(1.0, s / 100.0);
  Eigen::VectorXd& f = body.externalForces();
  for (int i : left) f[3 * i] = force / left.size();
  for (int i : right) f[3 * i] = -force / right.size();
}

/// The mean x of the nodes, m.
double meanX(const dc::Body& body, const std::vector<int>& nodes) {
  double x = 0.0;
  for (int i : nodes) x += body.positions()[3 * i] / nodes.size();
  return x;
}

/// The base held by its underside; the tops of the arms pushed towards each other with 2 N each,
/// ramped up over a second and held for one more: enough to bend each arm past the middle.
UEnd pushArmsTogether(bool self) {
  dc::SceneSpec spec = selfContactScene(self);
  spec.bodies[0].fixed.push_back(boxSelection({-1, -1, -1e-9}, {1, 1, 1e-9}));
  dc::Simulation sim(spec, {uMesh()});
  dc::Body& body = sim.bodies()[0];
  const std::vector<int> left =
      dc::selectNodes(body.mesh(), boxSelection({-1, -1, 0.3 - 1e-9}, {0.05 + 1e-9, 1, 1}));
  const std::vector<int> right =
      dc::selectNodes(body.mesh(), boxSelection({0.25 - 1e-9, -1, 0.3 - 1e-9}, {1, 1, 1}));
  UEnd end;
  end.run.tolerance = toleranceOf(body);
  std::vector<dc::StepReport> reports;
  for (int s = 1; s <= 200; ++s) {
    pushTips(body, left, right, s);
    sim.step(reports);
    end.run.self_contacts += reports[0].self_contacts;
    if (s % 5 == 0) end.run.deepest = std::max(end.run.deepest, deepestInsideItself(body, 0.06));
  }
  end.left_tip = meanX(body, left);
  end.right_tip = meanX(body, right);
  end.run.inverted = reports[0].inverted_elements;
  end.run.finite = body.stateIsFinite();
  return end;
}

}  // namespace

TEST(SelfContact, TheArmsOfAUPushedIntoEachOtherMeetAndStayApart) {
  const UEnd without = pushArmsTogether(false);
  // The case is hard: without self-contact the arms cross and sink deep into each other.
  ASSERT_GT(without.left_tip, without.right_tip);
  EXPECT_GT(without.run.deepest, 3 * without.run.tolerance);

  const UEnd with = pushArmsTogether(true);
  EXPECT_GT(with.run.self_contacts, 0);
  EXPECT_LE(with.run.deepest, with.run.tolerance);
  EXPECT_LT(with.left_tip, with.right_tip);
  EXPECT_GT(with.left_tip, 0.1);  // really pushed: each tip went most of the way to the middle
  EXPECT_LT(with.right_tip, 0.2);
  EXPECT_EQ(with.run.inverted, 0);
  EXPECT_TRUE(with.run.finite);
}

namespace {

// --- The same U made from its surface, on a grid not aligned with it ----------------------------

/// The U of uMesh as a closed surface: its outline in the x-z plane (counter-clockwise), 5 cm
/// deep along y.
dc::TriangleMesh uSurface() {
  const double outline[10][2] = {{0, 0},       {0.3, 0},     {0.3, 0.05}, {0.3, 0.3}, {0.25, 0.3},
                                 {0.25, 0.05}, {0.05, 0.05}, {0.05, 0.3}, {0, 0.3},   {0, 0.05}};
  dc::TriangleMesh mesh;
  for (double y : {0.0, 0.05}) {
    for (const auto& p : outline) mesh.vertices.emplace_back(p[0], y, p[1]);
  }
  // The face y = 0 looks along -y: counter-clockwise in x-z, as x cross z = -y. The far face
  // (+10) the other way round.
  const int faces[][3] = {{0, 1, 2}, {0, 2, 5}, {0, 5, 6}, {0, 6, 9},
                          {9, 6, 7}, {9, 7, 8}, {5, 2, 3}, {5, 3, 4}};
  for (const auto& f : faces) {
    mesh.triangles.emplace_back(f[0], f[1], f[2]);
    mesh.triangles.emplace_back(f[0] + 10, f[2] + 10, f[1] + 10);
  }
  for (int i = 0; i < 10; ++i) {
    const int j = (i + 1) % 10;
    deformable_sim::test::addQuad(mesh, i, i + 10, j + 10, j);
  }
  return mesh;
}

}  // namespace

// Voxelized on 4 cm cells, the U's grid stands up to 2 cm out of its surface, and its arms are
// two partial cells wide. Pushed as the mesh U is, its arms meet surface to surface. (Without
// self-contact its surface ends 1.8 cm inside itself and the arms cross.)
TEST(SelfContact, TheArmsOfAUMadeFromItsSurfaceMeetAndStayApart) {
  dc::VoxelSettings cells;
  cells.cell_size = 0.04;
  dc::SurfaceBody u = dc::bodyFromSurface(uSurface(), cells, nullptr);
  ASSERT_NEAR(u.voxels.enclosed_volume, (0.3 * 0.05 + 2 * 0.25 * 0.05) * 0.05, 1e-9);
  dc::SceneSpec spec = selfContactScene(true);
  spec.bodies[0].fixed.push_back(boxSelection({-1, -1, -1}, {1, 1, 0.0}));  // its lowest nodes
  dc::Simulation sim = deformable_sim::test::surfaceSimulation(spec, {u});
  dc::Body& body = sim.bodies()[0];
  const std::vector<int> left =
      dc::selectNodes(body.mesh(), boxSelection({-1, -1, 0.28}, {0.1, 1, 1}));
  const std::vector<int> right =
      dc::selectNodes(body.mesh(), boxSelection({0.2, -1, 0.28}, {1, 1, 1}));
  ASSERT_FALSE(left.empty());
  ASSERT_FALSE(right.empty());
  std::vector<dc::Triangle> triangles;
  for (const Eigen::Vector3i& t : u.surface.triangles()) triangles.push_back({t[0], t[1], t[2]});
  Eigen::VectorXd rest(3 * u.surface.numVertices()), x(rest.size());
  for (int v = 0; v < u.surface.numVertices(); ++v) {
    rest.segment<3>(3 * v) = u.surface.restPositions()[v];
  }
  const double tolerance = sim.bodyContact()->tolerance(0, 0);
  std::vector<dc::StepReport> reports;
  long self_contacts = 0;
  double deepest = 0.0;
  for (int s = 1; s <= 200; ++s) {
    pushTips(body, left, right, s);
    sim.step(reports);
    self_contacts += reports[0].self_contacts;
    if (s % 5 != 0) continue;
    dc::EmbeddedSurface& surface = *sim.embeddedSurface(0);
    surface.update(body.positions());
    for (int v = 0; v < surface.numVertices(); ++v) x.segment<3>(3 * v) = surface.positions()[v];
    deepest = std::max(deepest, deepestInsideItself(triangles, x, rest, 0.06));
  }
  EXPECT_GT(self_contacts, 0);
  EXPECT_LE(deepest, tolerance);
  EXPECT_LT(meanX(body, left), meanX(body, right));
  EXPECT_GT(meanX(body, left), 0.1);  // really pushed: each tip went most of the way to the middle
  EXPECT_EQ(reports[0].inverted_elements, 0);
  EXPECT_TRUE(body.stateIsFinite());
}

namespace {

// --- A strip folded over and pressed flat onto itself -------------------------------------------

constexpr double kStripLength = 0.4, kStripWidth = 0.04, kStripThickness = 0.01;

/// The strip lies on a floor with its end x = 0 held. Over a second its free end is carried over
/// the top, turned end for end, to 5 cm from the held end and 3 cm up, and held there. Then a
/// hand presses the folded half down onto the other with `press` N (ramped up over half a second)
/// on the 8 cm of its top between 8 and 16 cm from the held end, for one and a half seconds.
/// `lowest`: how low the underside of that part came while pressed, m.
SelfContactRun foldAndPress(bool self, double press, double* lowest) {
  dc::SceneSpec spec = selfContactScene(self);
  spec.effects.gravity = Eigen::Vector3d(0, 0, -9.81);
  spec.bodies[0].fixed.push_back(boxSelection({-1, -1, -1}, {1e-9, 1, 1}));
  spec.obstacles = {deformable_sim::test::floorBox({2.0, 2.0, 0.2})};
  dc::Mesh strip = dc::makeBoxMesh({0, 0, 0}, {kStripLength, kStripWidth, kStripThickness},
                                   {20, 2, 1}, dc::BoxElement::kHexahedron);
  strip.incompatible_modes = true;  // one cell through: plain hexahedra would lock in bending
  dc::Simulation sim(spec, {strip});
  dc::Body& body = sim.bodies()[0];
  const auto select = [&](double x0, double x1, double z) {
    return dc::selectNodes(body.mesh(),
                           boxSelection({x0 - 1e-9, -1, z - 1e-9}, {x1 + 1e-9, 1, z + 1e-9}));
  };
  const std::vector<int> end =
      dc::selectNodes(body.mesh(), boxSelection({kStripLength - 1e-9, -1, -1}, {1, 1, 1}));
  // Turned over, the part 0.24 to 0.32 m along the strip lies 0.16 to 0.08 m from the held end.
  const std::vector<int> pressed_top = select(0.24, 0.32, 0.0),
                         pressed_underside = select(0.24, 0.32, kStripThickness);
  const Eigen::Vector3d end_centre(kStripLength, kStripWidth / 2, kStripThickness / 2);
  SelfContactRun run;
  run.tolerance = toleranceOf(body);
  *lowest = std::numeric_limits<double>::infinity();
  std::vector<dc::StepReport> reports;
  for (int s = 1; s <= 250; ++s) {
    if (s <= 100) {  // the free end goes over the top on half an ellipse, turning with it
      const double phi = M_PI * s / 100.0;
      const Eigen::Vector3d centre(0.225 + 0.175 * std::cos(phi), kStripWidth / 2,
                                   0.005 + 0.12 * std::sin(phi) + 0.015 * (1.0 - std::cos(phi)));
      const Eigen::Matrix3d turn = Eigen::AngleAxisd(-phi, Eigen::Vector3d::UnitY()).matrix();
      std::vector<Eigen::Vector3d> targets;
      for (int i : end)
        targets.push_back(centre + turn * (body.restPositions().segment<3>(3 * i) - end_centre));
      body.setNodeTargets(end, targets);
    } else {
      const double force = press * std::min(1.0, (s - 100) / 50.0);
      Eigen::VectorXd& f = body.externalForces();
      for (int i : pressed_top) f[3 * i + 2] = -force / pressed_top.size();
    }
    sim.step(reports);
    run.self_contacts += reports[0].self_contacts;
    if (s % 5 == 0) run.deepest = std::max(run.deepest, deepestInsideItself(body, 0.1));
    if (s <= 100) continue;
    for (int i : pressed_underside) *lowest = std::min(*lowest, body.positions()[3 * i + 2]);
  }
  run.inverted = reports[0].inverted_elements;
  run.finite = body.stateIsFinite();
  return run;
}

}  // namespace

TEST(SelfContact, AStripFoldedOverAndPressedFlatKeepsItsLayersApart) {
  double lowest_without = 0.0, lowest_with = 0.0;
  const SelfContactRun without = foldAndPress(false, 5.0, &lowest_without);
  const SelfContactRun with = foldAndPress(true, 5.0, &lowest_with);
  // The case is hard: without self-contact the folded half is pressed through the other onto
  // the floor.
  ASSERT_LT(lowest_without, 0.25 * kStripThickness);
  ASSERT_GT(without.deepest, without.tolerance);
  EXPECT_GT(with.self_contacts, 0);
  EXPECT_LE(with.deepest, with.tolerance);
  EXPECT_GT(lowest_with, kStripThickness - with.tolerance);  // it rests on the lower half
  EXPECT_EQ(with.inverted, 0);
  EXPECT_TRUE(with.finite);
}
