// An obstacle's edges stay out of a body's faces, as the body's points stay out of obstacles:
// a box turned to press one edge into a soft cube's top face between its nodes sinks into it by
// no more than the contact tolerance, a primitive box or a box of triangles alike.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/core/geometry/triangle_aabb_tree.h"
#include "deformable_sim/core/geometry/triangle_mesh.h"
#include "deformable_sim/core/geometry/triangle_mesh_shape.h"
#include "deformable_sim/core/geometry/winding_number.h"
#include "deformable_sim/core/session/simulation.h"
#include "scene_builder.h"
#include "simulation_test_helpers.h"

namespace dc = deformable_sim::core;

namespace {

constexpr double kSide = 0.04;  // m, the cube: 4 x 4 x 4 cells of 1 cm
constexpr double kBar = 0.01;   // m, the bar's square section
/// How far an obstacle's edge may be inside the body, m: what a point of the body may be off an
/// obstacle's face and still touch it.
constexpr double kTolerance = 1e-4;

// The cube's surface where its nodes are now, for distances and inside tests.
dc::TriangleMesh surfaceOf(const dc::Body& body) {
  dc::TriangleMesh surface;
  for (int i = 0; i < body.numNodes(); ++i)
    surface.vertices.emplace_back(body.positions().segment<3>(3 * i));
  for (const dc::Face& f : dc::extractBoundary(body.mesh())) {
    surface.triangles.emplace_back(f.nodes[0], f.nodes[1], f.nodes[2]);
    if (f.size() == 4) surface.triangles.emplace_back(f.nodes[0], f.nodes[2], f.nodes[3]);
  }
  return surface;
}

// How deep the bar's lower edge is inside the cube, m (0 when it is out), over points along it.
double edgeDepth(const dc::Body& body, const dc::PlacedShape& bar) {
  const dc::TriangleMesh surface = surfaceOf(body);
  const dc::TriangleAabbTree tree(surface);
  double deepest = 0.0;
  for (int k = 0; k <= 40; ++k) {  // the edge runs along y, through the cube's top
    const Eigen::Vector3d local(0.0, kSide * (k / 40.0 - 0.5), -std::sqrt(0.5) * kBar);
    const Eigen::Vector3d p = bar.pose.translation() + local;
    if (dc::exactWindingNumber(surface, p) < 0.5) continue;
    deepest = std::max(deepest, std::sqrt(tree.nearest(surface, p).squared_distance));
  }
  return deepest;
}

// The bar as a primitive box, or as a closed mesh of the same box's twelve triangles.
dc::PlacedShape edgeFirstBar(dc::Shape::Kind kind = dc::Shape::Kind::kBox) {
  dc::PlacedShape bar;
  bar.name = "bar";
  const Eigen::Vector3d size(kBar, 0.08, kBar);
  bar.shape.kind = kind;
  if (kind == dc::Shape::Kind::kBox) bar.shape.size = size;
  if (kind == dc::Shape::Kind::kMesh)
    bar.shape.mesh =
        std::make_shared<const dc::TriangleMeshShape>(dc::boxSurface(-0.5 * size, 0.5 * size));
  bar.pose.linear() = Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitY()).toRotationMatrix();
  return bar;
}

// The bar with its lower edge at `edge_height`, along y, 5 mm off the cube's middle: half way
// between two columns of nodes.
dc::PlacedShape barAt(dc::PlacedShape bar, double edge_height) {
  bar.pose.translation() = Eigen::Vector3d(0.005, 0.0, edge_height + std::sqrt(0.5) * kBar);
  return bar;
}

dc::SceneSpec cubeUnderABar(dc::Shape::Kind kind = dc::Shape::Kind::kBox, double friction = 0.5) {
  dc::SceneSpec spec = deformable_sim::test::dampedTable(friction, {0.4, 0.4, 0.04});
  spec.obstacles.push_back(barAt(edgeFirstBar(kind), kSide + 0.01));
  spec.bodies.push_back(deformable_sim::test::boxBody("cube", {-0.5 * kSide, -0.5 * kSide, 0.0},
                                                      {0.5 * kSide, 0.5 * kSide, kSide}, {4, 4, 4},
                                                      {3.0e4, 0.3, 150.0}));
  return spec;
}

}  // namespace

TEST(ObstacleEdges, TheMeterReadsHowDeepAnEdgeIsInAnUndeformedCube) {
  // The meter the next test relies on: an edge 4 mm below the top of a cube at rest is 4 mm
  // inside; 1 mm above it, out.
  const dc::Simulation sim = deformable_sim::test::boxMeshSimulation(cubeUnderABar());
  EXPECT_NEAR(edgeDepth(sim.bodies()[0], barAt(edgeFirstBar(), kSide - 0.004)), 0.004, 1e-12);
  EXPECT_EQ(edgeDepth(sim.bodies()[0], barAt(edgeFirstBar(), kSide + 0.001)), 0.0);
}

// The bar comes down to 4 mm below the cube's top in 0.5 s and stays: how deep its edge ends up,
// and how hard it presses down.
// Then it rises 2 cm above the top in 0.2 s and stays there for 0.5 s: where the cube ends.
struct Pressed {
  double depth = 0.0, force = 0.0;
  double lowest_after = 0.0;   ///< m, the cube's lowest node after the bar rose
  double highest_after = 0.0;  ///< m, its highest
  double force_after = 0.0;    ///< N, the bar's push down after it rose
};

Pressed pressEdgeFirst(dc::Shape::Kind kind) {
  dc::Simulation sim = deformable_sim::test::boxMeshSimulation(cubeUnderABar(kind));
  std::vector<dc::StepReport> reports;
  for (int s = 0; s < 50; ++s) sim.step(reports);
  for (int s = 1; s <= 50; ++s) {
    sim.obstacles()[1] = barAt(edgeFirstBar(kind), kSide + 0.01 - 0.014 * s / 50.0);
    sim.step(reports);
  }
  for (int s = 0; s < 20; ++s) sim.step(reports);
  Pressed pressed{edgeDepth(sim.bodies()[0], sim.obstacles()[1]),
                  -sim.obstacleContacts(0)[1].force.z()};
  for (int s = 1; s <= 20; ++s) {
    sim.obstacles()[1] = barAt(edgeFirstBar(kind), kSide - 0.004 + 0.024 * s / 20.0);
    sim.step(reports);
  }
  for (int s = 0; s < 50; ++s) sim.step(reports);
  const Eigen::VectorXd& x = sim.bodies()[0].positions();
  pressed.lowest_after = pressed.highest_after = x[2];
  for (int i = 0; i < sim.bodies()[0].numNodes(); ++i) {
    pressed.lowest_after = std::min(pressed.lowest_after, x[3 * i + 2]);
    pressed.highest_after = std::max(pressed.highest_after, x[3 * i + 2]);
  }
  pressed.force_after = -sim.obstacleContacts(0)[1].force.z();
  return pressed;
}

// Lifted away, the bar lets the cube go: it stands on the table at its own height again (within
// 1 mm), and the bar pushes on nothing. A face held against an obstacle's edge is held only while
// it pushes.
void expectLetGo(const Pressed& pressed) {
  EXPECT_NEAR(pressed.lowest_after, 0.0, 1e-3) << "the cube left the table with the bar";
  EXPECT_NEAR(pressed.highest_after, kSide, 1e-3);
  EXPECT_EQ(pressed.force_after, 0.0);
}

// [contact-space] reports that the edges and corners of box obstacles sink about 1 mm into a
// body's faces, unseen by contact that looks only at the body's points. Here the edge comes down
// between two columns of nodes, 5 mm from each: the bar feels nothing and its edge ends 3.96 mm
// inside the cube (the whole 4 mm it was pressed), until contact looks at the obstacle's features.
TEST(ObstacleEdges, ABoxPressedEdgeFirstStaysOutOfTheFaceBetweenNodes) {
  const Pressed pressed = pressEdgeFirst(dc::Shape::Kind::kBox);
  EXPECT_GT(pressed.force, 0.1) << "the bar did not press";
  EXPECT_LE(pressed.depth, kTolerance);
  expectLetGo(pressed);
}

// The same bar as a mesh obstacle (a URDF link's collision mesh, a scene's `mesh:` obstacle): its
// edge, between two of its triangles, stays out of the face as the primitive's does, and presses
// as hard.
TEST(ObstacleEdges, AMeshBoxPressedEdgeFirstStaysOutOfTheFaceBetweenNodes) {
  const Pressed mesh = pressEdgeFirst(dc::Shape::Kind::kMesh);
  EXPECT_GT(mesh.force, 0.1) << "the bar did not press";
  EXPECT_LE(mesh.depth, kTolerance);
  EXPECT_NEAR(mesh.force, pressEdgeFirst(dc::Shape::Kind::kBox).force, 0.05 * mesh.force);
  expectLetGo(mesh);
}

// The edge comes down 13 mm in one step, to 3 mm below the top, as deep as a face is half wide:
// put out of the faces all the same, by the box and by the mesh.
TEST(ObstacleEdges, AnEdgeThreeMillimetresDeepWithinOneStepIsPutOut) {
  for (dc::Shape::Kind kind : {dc::Shape::Kind::kBox, dc::Shape::Kind::kMesh}) {
    dc::Simulation sim = deformable_sim::test::boxMeshSimulation(cubeUnderABar(kind));
    std::vector<dc::StepReport> reports;
    for (int s = 0; s < 50; ++s) sim.step(reports);
    sim.obstacles()[1] = barAt(edgeFirstBar(kind), kSide - 0.003);
    for (int s = 0; s < 20; ++s) sim.step(reports);
    EXPECT_GT(-sim.obstacleContacts(0)[1].force.z(), 0.1) << int(kind);
    EXPECT_LE(edgeDepth(sim.bodies()[0], sim.obstacles()[1]), kTolerance) << int(kind);
  }
}

// The least distance of the cube's nodes from the bar, m: above zero, the nodes do not touch it
// and the bar holds the cube by its faces alone.
double nodesClearOf(const dc::Body& body, const dc::PlacedShape& bar) {
  double least = std::numeric_limits<double>::infinity();
  const Eigen::Isometry3d to_bar = bar.pose.inverse();
  for (int i = 0; i < body.numNodes(); ++i) {
    const Eigen::Vector3d x = body.positions().segment<3>(3 * i);
    least = std::min(least, dc::signedDistance(bar.shape, to_bar * x));
  }
  return least;
}

struct Drag {
  double ratio = 0.0;      ///< the force along the edge over the push, summed over the window
  double clearance = 0.0;  ///< m, the least distance of a node from the bar in the window
};

// Pressed 4 mm in, the bar is drawn 2 cm along its edge in 1 s over the cube, whose base is held:
// the force along the edge over the push, and the nodes' clearance, over the middle of the draw.
Drag dragAlongTheEdge(dc::Shape::Kind kind, double friction) {
  dc::SceneSpec spec = cubeUnderABar(kind, friction);
  spec.bodies[0].fixed.push_back(
      deformable_sim::test::boxSelection({-1, -1, -1e-9}, {1, 1, 1e-9}));  // its base
  dc::Simulation sim = deformable_sim::test::boxMeshSimulation(spec);
  std::vector<dc::StepReport> reports;
  const auto barAtShift = [&](double height, double shift) {
    dc::PlacedShape bar = barAt(edgeFirstBar(kind), height);
    bar.pose.translation().y() += shift;
    return bar;
  };
  for (int s = 1; s <= 50; ++s) {
    sim.obstacles()[1] = barAtShift(kSide + 0.01 - 0.014 * s / 50.0, 0.0);
    sim.step(reports);
  }
  for (int s = 0; s < 20; ++s) sim.step(reports);
  double along = 0.0, push = 0.0;
  Drag drag;
  drag.clearance = std::numeric_limits<double>::infinity();
  for (int s = 1; s <= 100; ++s) {
    sim.obstacles()[1] = barAtShift(kSide - 0.004, 0.02 * s / 100.0);
    sim.step(reports);
    if (s <= 30 || s > 70) continue;
    along += sim.obstacleContacts(0)[1].force.y();
    push += sim.obstacleContacts(0)[1].force.z();
    drag.clearance = std::min(drag.clearance, nodesClearOf(sim.bodies()[0], sim.obstacles()[1]));
  }
  drag.ratio = -along / push;  // the bar moves along +y: it drags the cube along +y, pushes down
  return drag;
}

// [contact-space] asks for Coulomb friction in one model for every kind of contact: the faces an
// obstacle's edge presses into hold on to it as the body's points do, judged with them by their
// summed forces, and slide with μ times their push. Before, they only pushed (the ratio was 0).
// The cube's nodes stay clear of the box bar: its faces alone carry the drag (a node of the
// sheared top touches the mesh bar now and then, and the points take over for that step). Below
// μ on average (a step's own ratio may pass μ while a sliding patch gives back what it held
// beyond the cone), by the stick-slip of nodes that catch up with the bar and stick until their
// patch leaves the cone again; the cube's points under the same bar laid flat pull with about
// 0.8 μ (doc/physics.md).
TEST(ObstacleEdges, ABarDrawnAlongItsEdgeDragsTheCubesFacesByFrictionBelowMu) {
  for (dc::Shape::Kind kind : {dc::Shape::Kind::kBox, dc::Shape::Kind::kMesh}) {
    for (double mu : {0.5, 1.0}) {
      const Drag drag = dragAlongTheEdge(kind, mu);
      EXPECT_GT(drag.ratio, 0.5 * mu) << int(kind) << " mu " << mu;
      EXPECT_LT(drag.ratio, 1.001 * mu) << int(kind) << " mu " << mu;
      if (kind == dc::Shape::Kind::kBox) {
        EXPECT_GT(drag.clearance, 0.0) << "mu " << mu;
      }
    }
    EXPECT_LT(std::abs(dragAlongTheEdge(kind, 0.0).ratio), 0.01) << int(kind);
  }
}
