#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "deformable_sim/core/elements/parameter_limits.h"
#include "deformable_sim/core/session/default_scene.h"
#include "deformable_sim/io/mesh_reader.h"
#include "deformable_sim/io/scene_file.h"

namespace dc = deformable_sim::core;
namespace dio = deformable_sim::io;

namespace {

const char* kScene = R"(
dt: 0.005
effects: {gravity: [0, 0, -9.81], warping: true, damping: {mass: 0.5, stiffness: 0.01}}
solver: {method: direct, tolerance: 1.0e-8, max_iterations: 50}
static: {load_steps: 3}
bodies:
  - name: beam
    mesh: {box: {min: [0, -0.05, -0.05], max: [1, 0.05, 0.05], cells: [10, 2, 2]}}
    model: fem
    material: {youngs_modulus: 2.0e6, poisson_ratio: 0.25, density: 800.0}
    fixed: [{box: {min: [-1.0e-6, -1, -1], max: [1.0e-6, 1, 1]}}, {nodes: [13]}]
    loads:
      - {box: {min: [0.999, -1, -1], max: [1.001, 1, 1]}, traction: [0, 0, -2.5]}
      - {nodes: [7], total_force: [0, 0, -0.01]}
)";

// The message of the SceneError thrown by parsing (or building) `yaml`, or "" if none.
std::string errorOf(const std::string& yaml, bool build = false) {
  try {
    const dc::SceneSpec spec = dio::parseScene(yaml, "test.yaml", ".");
    if (build) dio::buildSimulation(spec, nullptr);
  } catch (const dio::SceneError& e) {
    return e.what();
  }
  return "";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

}  // namespace

TEST(SceneFile, ReadsEveryKey) {
  const dc::SceneSpec spec = dio::parseScene(kScene, "test.yaml", "/scenes");
  EXPECT_EQ(spec.dt, 0.005);
  ASSERT_TRUE(spec.effects.gravity.has_value());
  EXPECT_EQ(*spec.effects.gravity, Eigen::Vector3d(0, 0, -9.81));
  EXPECT_TRUE(spec.effects.warping);
  ASSERT_TRUE(spec.effects.damping.has_value());
  EXPECT_EQ(spec.effects.damping->mass, 0.5);
  EXPECT_EQ(spec.effects.damping->stiffness, 0.01);
  EXPECT_EQ(spec.solver.method, dc::SolverSettings::Method::kDirect);
  EXPECT_EQ(spec.solver.tolerance, 1e-8);
  EXPECT_EQ(spec.solver.max_iterations, 50);
  EXPECT_EQ(spec.solver.preconditioner, dc::SolverSettings::Preconditioner::kTwoLevel);  // default
  EXPECT_EQ(spec.solver.warm_start, dc::SolverSettings::WarmStart::kProjected);          // default
  EXPECT_EQ(spec.solver.previous_solutions, 32);
  EXPECT_EQ(spec.statics.load_steps, 3);
  ASSERT_EQ(spec.bodies.size(), 1u);
  const dc::BodySpec& body = spec.bodies[0];
  EXPECT_EQ(body.name, "beam");
  ASSERT_TRUE(body.box_mesh.has_value());
  EXPECT_EQ(body.box_mesh->cells, Eigen::Vector3i(10, 2, 2));
  EXPECT_EQ(body.material.youngs_modulus, 2.0e6);
  EXPECT_EQ(body.material.poisson_ratio, 0.25);
  EXPECT_EQ(body.material.density, 800.0);
  ASSERT_EQ(body.fixed.size(), 2u);
  EXPECT_EQ(body.fixed[1].kind, dc::NodeSelection::Kind::kNodes);
  EXPECT_EQ(body.fixed[1].node_numbers, std::vector<long>{13});
  ASSERT_EQ(body.loads.size(), 2u);
  EXPECT_EQ(body.loads[0].kind, dc::LoadSpec::Kind::kTraction);
  EXPECT_EQ(body.loads[1].kind, dc::LoadSpec::Kind::kTotalForce);
  EXPECT_EQ(body.loads[1].value, Eigen::Vector3d(0, 0, -0.01));
}

TEST(SceneFile, EffectsNotNamedAreOff) {
  const dc::SceneSpec spec = dio::parseScene(
      "bodies: [{name: b, mesh: {box: {min: [0,0,0], max: [1,1,1], cells: [1,1,1]}}, material: "
      "{}}]",
      "minimal.yaml", ".");
  EXPECT_FALSE(spec.effects.gravity.has_value());
  EXPECT_FALSE(spec.effects.warping);
  EXPECT_FALSE(spec.effects.damping.has_value());
}

TEST(SceneFile, BuildsTheSimulationWithLoadsAndConstraints) {
  dc::Simulation sim = dio::buildSimulation(dio::parseScene(kScene, "test.yaml", "."), nullptr);
  ASSERT_EQ(sim.bodies().size(), 1u);
  const dc::Body& beam = sim.body("beam");
  EXPECT_EQ(numConstrained(beam), 9 + 1);  // the 3x3 clamped face and node 13
  const Eigen::Vector3d load = beam.externalForces().reshaped(3, beam.numNodes()).rowwise().sum();
  EXPECT_NEAR((load - Eigen::Vector3d(0, 0, -0.035)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(beam.externalForces()[3 * 6 + 2], -0.01, 1e-15);  // node 7 is index 6
  EXPECT_THROW(sim.body("nope"), std::out_of_range);
}

TEST(SceneFile, ResolvesMeshPathsAgainstTheSceneFile) {
  const dc::SceneSpec spec = dio::parseScene(
      "bodies: [{name: b, mesh: meshes/beam.msh, material: {}}]", "s.yaml", "/data/scenes");
  EXPECT_EQ(spec.bodies[0].mesh, "/data/scenes/meshes/beam.msh");
}

TEST(SceneFile, ChoosesThePreconditionerAndItsRefresh) {
  const dc::SceneSpec spec = dio::parseScene(
      replaced(kScene, "method: direct",
               "method: cg, preconditioner: block_jacobi, coarse_refresh_interval: 3, threads: 2, "
               "warm_start: last_velocity, max_rotation_updates: 0"),
      "test.yaml", ".");
  EXPECT_EQ(spec.solver.max_rotation_updates, 0);
  EXPECT_EQ(spec.solver.preconditioner, dc::SolverSettings::Preconditioner::kBlockJacobi);
  EXPECT_EQ(spec.solver.coarse_refresh_interval, 3);
  EXPECT_EQ(spec.solver.threads, 2);
  EXPECT_EQ(spec.solver.warm_start, dc::SolverSettings::WarmStart::kLastVelocity);
  const dc::SceneSpec projected =
      dio::parseScene(replaced(kScene, "method: direct",
                               "method: cg, warm_start: projected, previous_solutions: 8"),
                      "test.yaml", ".");
  EXPECT_EQ(projected.solver.warm_start, dc::SolverSettings::WarmStart::kProjected);
  EXPECT_EQ(projected.solver.previous_solutions, 8);
}

// The scene reader refuses a material, damping or solver value with the words the bodies and live
// tuning use (core/parameter_limits.h), at the value's line.
TEST(SceneFile, ParametersAreRefusedAsTheBodiesAndLiveTuningRefuseThem) {
  using dc::Parameter;
  const struct {
    const char* from;
    const char* to;
    Parameter parameter;
    double value;
    const char* where;
  } cases[] = {
      {"youngs_modulus: 2.0e6", "youngs_modulus: -5", Parameter::kYoungsModulus, -5.0,
       "test.yaml:10: bodies[0].material.youngs_modulus: "},
      {"density: 800.0", "density: 0", Parameter::kDensity, 0.0,
       "test.yaml:10: bodies[0].material.density: "},
      {"mass: 0.5", "mass: -1", Parameter::kDampingMass, -1.0,
       "test.yaml:3: effects.damping.mass: "},
      {"stiffness: 0.01", "stiffness: -0.01", Parameter::kDampingStiffness, -0.01,
       "test.yaml:3: effects.damping.stiffness: "},
      {"tolerance: 1.0e-8", "tolerance: 0", Parameter::kSolverTolerance, 0.0,
       "test.yaml:4: solver.tolerance: "},
      {"max_iterations: 50", "max_iterations: 0", Parameter::kSolverMaxIterations, 0.0,
       "test.yaml:4: solver.max_iterations: "},
  };
  for (const auto& c : cases) {
    EXPECT_EQ(errorOf(replaced(kScene, c.from, c.to)),
              c.where + dc::parameterProblem(c.parameter, c.value));
  }
}

TEST(SceneFile, ErrorsNameTheFileLineAndKey) {
  EXPECT_EQ(errorOf(replaced(kScene, "youngs_modulus", "youngs_modulu")),
            "test.yaml:10: bodies[0].material.youngs_modulu: unknown key (expected one of: "
            "density, law, poisson_ratio, youngs_modulus)");
  EXPECT_EQ(errorOf(replaced(kScene, "density: 800.0", "density: heavy")),
            "test.yaml:10: bodies[0].material.density: expected a number");
  EXPECT_EQ(errorOf(replaced(kScene, "poisson_ratio: 0.25", "poisson_ratio: 0.5")),
            "test.yaml:10: bodies[0].material.poisson_ratio: must be in (-1, 0.5)");
  EXPECT_EQ(errorOf(replaced(kScene, "density: 800.0", "density: .nan")),
            "test.yaml:10: bodies[0].material.density: must be finite");
  EXPECT_EQ(errorOf(replaced(kScene, "gravity: [0, 0, -9.81]", "gravity: [0, -9.81]")),
            "test.yaml:3: effects.gravity: expected a list of 3 numbers");
  EXPECT_EQ(errorOf(replaced(kScene, "method: direct", "method: magic")),
            "test.yaml:4: solver.method: 'magic' is not one of: cg, direct");
  EXPECT_EQ(errorOf(replaced(kScene, "method: direct", "method: cg, preconditioner: ilu")),
            "test.yaml:4: solver.preconditioner: 'ilu' is not one of: two_level, block_jacobi, "
            "factorization");
  EXPECT_EQ(errorOf(replaced(kScene, "method: direct", "method: cg, coarse_refresh_interval: 0")),
            "test.yaml:4: solver.coarse_refresh_interval: must be >= 1");
  EXPECT_EQ(errorOf(replaced(kScene, "method: direct", "method: cg, warm_start: zero")),
            "test.yaml:4: solver.warm_start: 'zero' is not one of: projected, extrapolated, "
            "last_velocity");
  EXPECT_EQ(errorOf(replaced(kScene, "method: direct", "method: cg, previous_solutions: 0")),
            "test.yaml:4: solver.previous_solutions: must be in 1 .. 256");
  EXPECT_EQ(errorOf(replaced(kScene, "method: direct", "method: cg, threads: 0")),
            "test.yaml:4: solver.threads: must be >= 1");
  EXPECT_EQ(errorOf(replaced(kScene, "dt: 0.005", "dt: -1")), "test.yaml:2: dt: must be > 0");
  EXPECT_EQ(errorOf(replaced(kScene, "model: fem", "model: soft")),
            "test.yaml:9: bodies[0].model: 'soft' is not one of: fem, pseudo_rigid, rigid");
  EXPECT_EQ(errorOf(replaced(kScene, "traction: [0, 0, -2.5]", "pressure: 3")),
            "test.yaml:13: bodies[0].loads[0].pressure: unknown key (expected one of: box, "
            "nodes, sphere, total_force, traction, wrench)");
  EXPECT_EQ(errorOf("bodies: [}"), "test.yaml:1: not valid YAML: illegal flow end");
  EXPECT_EQ(errorOf("dt: 0.1"), "test.yaml:1: bodies: missing: a scene needs at least one body");
}

TEST(SceneFile, EmptyOrUnknownSelectionsAreErrorsNamingTheKey) {
  EXPECT_EQ(
      errorOf(replaced(kScene, "{nodes: [13]}", "{box: {min: [5, 5, 5], max: [6, 6, 6]}}"), true),
      "test.yaml:11: bodies[0].fixed[1]: selects no node");
  EXPECT_EQ(errorOf(replaced(kScene, "{nodes: [13]}", "{nodes: [13, 100000]}"), true),
            "test.yaml:11: bodies[0].fixed[1]: node 100000 is not a node of the mesh");
  // A traction needs whole boundary faces inside its selection.
  EXPECT_EQ(errorOf(replaced(kScene, "{box: {min: [0.999, -1, -1], max: [1.001, 1, 1]}, traction",
                             "{nodes: [7], traction"),
                    true),
            "test.yaml:13: bodies[0].loads[0]: traction selects no boundary face (all nodes of a "
            "boundary face must be selected)");
}

// Found by fuzzing: a key that is not a name (a list, a map, a null) made yaml-cpp throw its own
// exception out of the parser instead of a SceneError.
TEST(SceneFile, KeysThatAreNotNamesAreErrorsNamingTheKey) {
  EXPECT_EQ(errorOf("{[1, 2]: 3}"),
            "test.yaml:1: scene: expected a key name, found a list, map or null");
  EXPECT_EQ(errorOf(replaced(kScene, "min: [0, -0.05", "[1]: 1, min: [0, -0.05")),
            "test.yaml:8: bodies[0].mesh.box: expected a key name, found a list, map or null");
  EXPECT_EQ(errorOf(replaced(kScene, "model: fem", "groups: {{a: 1}: {nodes: [1]}}")),
            "test.yaml:9: bodies[0].groups: expected a key name, found a list, map or null");
}

// The bound a user-facing parser needs: cells: [1e10, 1, 1] overflowed the conversion to int
// (undefined behaviour), and [2000, 2000, 2000] asked for 4.8e10 tetrahedra.
TEST(SceneFile, BoxMeshCellsAreBounded) {
  EXPECT_EQ(errorOf(replaced(kScene, "cells: [10, 2, 2]", "cells: [1e10, 1, 1]")),
            "test.yaml:8: bodies[0].mesh.box.cells: more than 1000000 cells in all");
  EXPECT_EQ(errorOf(replaced(kScene, "cells: [10, 2, 2]", "cells: [2000, 2000, 2000]")),
            "test.yaml:8: bodies[0].mesh.box.cells: more than 1000000 cells in all");
  EXPECT_EQ(errorOf(replaced(kScene, "cells: [10, 2, 2]", "cells: [1000, 1000, 1]")), "");
}

TEST(SceneFile, MissingFileIsAClearError) {
  try {
    dio::readSceneFile("/nonexistent/scene.yaml");
    FAIL();
  } catch (const dio::SceneError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/scene.yaml: cannot open the scene file");
  }
}

TEST(SceneFile, GroupsAndWrenchLoads) {
  const std::string yaml = replaced(
      kScene, "    loads:\n",
      "    groups: {tip: {box: {min: [0.999, -1, -1], max: [1.001, 1, 1]}}, one: {nodes: [7]}}\n"
      "    wrench_radius: 0.2\n"
      "    loads:\n"
      "      - {box: {min: [0.999, -1, -1], max: [1.001, 1, 1]},"
      " wrench: {force: [0, 1, 0], torque: [0.3, 0, 0]}}\n");
  const dc::SceneSpec spec = dio::parseScene(yaml, "test.yaml", ".");
  ASSERT_EQ(spec.bodies[0].groups.size(), 2u);
  EXPECT_EQ(spec.bodies[0].wrench_radius, 0.2);
  ASSERT_EQ(spec.bodies[0].loads[0].kind, dc::LoadSpec::Kind::kWrench);
  dc::Simulation sim = dio::buildSimulation(spec, nullptr);
  const dc::Body& body = sim.bodies()[0];
  EXPECT_EQ(body.mesh().groups.at("tip").size(), 9u);
  EXPECT_EQ(body.mesh().groups.at("one").size(), 1u);
  EXPECT_EQ(sim.wrenchRadius(0), 0.2);
  // Net load: the wrench's force plus the traction (2.5 Pa on 0.01 m^2) and the 0.01 N point load.
  const Eigen::Vector3d net = body.externalForces().reshaped(3, body.numNodes()).rowwise().sum();
  EXPECT_TRUE(net.isApprox(Eigen::Vector3d(0, 1, -0.025 - 0.01), 1e-12)) << net.transpose();
  EXPECT_EQ(errorOf(replaced(yaml, "torque: [0.3, 0, 0]", "torque: [0.3, 0]")),
            "test.yaml:15: bodies[0].loads[0].wrench.torque: expected a list of 3 numbers");
  EXPECT_EQ(errorOf(replaced(yaml, "one: {nodes: [7]}",
                             "one: {sphere: {center: [5, 5, 5], radius: 0.1}}"),
                    true),
            "test.yaml:12: bodies[0].groups.one: selects no node");
}

TEST(SceneFile, ABodyStartsWithItsVelocityUnlessItIsHeld) {
  const std::string free = replaced(
      replaced(kScene,
               "    fixed: [{box: {min: [-1.0e-6, -1, -1], max: [1.0e-6, 1, 1]}}, {nodes: [13]}]\n",
               ""),
      "    model: fem\n", "    model: fem\n    velocity: [5, 0, -1]\n");
  dc::Simulation sim = dio::buildSimulation(dio::parseScene(free, "test.yaml", "."), nullptr);
  const dc::Body& body = sim.bodies()[0];
  for (int i = 0; i < body.numNodes(); ++i) {
    ASSERT_EQ(body.velocities().segment<3>(3 * i), Eigen::Vector3d(5, 0, -1)) << i;
  }
  EXPECT_EQ(
      errorOf(replaced(kScene, "    model: fem\n", "    model: fem\n    velocity: [5, 0, -1]\n"),
              true),
      "test.yaml:10: bodies[0].velocity: a body with fixed nodes starts at rest");
  EXPECT_EQ(errorOf(replaced(free, "velocity: [5, 0, -1]", "velocity: [5, .nan, -1]")),
            "test.yaml:10: bodies[0].velocity[1]: must be finite");
}

TEST(SceneFile, BodiesChooseTheirModelAndChangeTheScenesEffects) {
  const std::string yaml = replaced(kScene, "    model: fem\n", R"(    model: rigid
    effects: {gravity: off, damping: {mass: 2.0}, reactions: false}
)");
  const dc::SceneSpec spec = dio::parseScene(yaml, "test.yaml", ".");
  const dc::BodySpec& body = spec.bodies[0];
  EXPECT_EQ(body.model, dc::BodyModel::kRigid);
  ASSERT_TRUE(body.effects.has_value());
  EXPECT_FALSE(body.effects->gravity.has_value());
  ASSERT_TRUE(body.effects->damping.has_value());
  EXPECT_EQ(body.effects->damping->mass, 2.0);
  EXPECT_EQ(body.effects->damping->stiffness, 0.0);
  EXPECT_FALSE(body.effects->reactions);
  EXPECT_TRUE(body.effects->warping);  // not named: the scene's
  EXPECT_TRUE(spec.effects.gravity.has_value());
  EXPECT_EQ(dio::parseScene(replaced(kScene, "model: fem", "model: pseudo_rigid"), "t", ".")
                .bodies[0]
                .model,
            dc::BodyModel::kPseudoRigid);
  // A body has its say on contact between bodies and with itself, not on friction.
  EXPECT_EQ(
      errorOf(replaced(kScene, "    model: fem\n", "    effects: {contact: {friction: 1}}\n")),
      "test.yaml:9: bodies[0].effects.contact.friction: unknown key (expected one of: "
      "bodies, self)");
  EXPECT_EQ(errorOf(replaced(kScene, "    model: fem\n",
                             "    model: rigid\n    effects: {plasticity: {yield: 0.1}}\n"),
                    true),
            "test.yaml:7: bodies[0]: body 'beam': plasticity needs a finite-element body (rigid "
            "bodies deform homogeneously or not at all)");
}

// Written as a file and read as a user's scene is: the messages name its path.
class SceneFileOnDisk : public ::testing::Test {
 protected:
  void SetUp() override {
    // Unique: test runs of several workspaces on one machine must not delete each other's files.
    std::string pattern =
        (std::filesystem::temp_directory_path() / "deformable_sim_scene_XXXXXX").string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    directory_ = pattern;
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }

  std::string write(const std::string& yaml) const {
    const std::string path = (directory_ / "scene.yaml").string();
    std::ofstream(path) << yaml;
    return path;
  }

  std::filesystem::path directory_;
};

// A mesh file that is not there is an error of the scene: the message says which entry names it.
TEST_F(SceneFileOnDisk, MissingMeshFileNamesTheSceneFileLineAndKey) {
  const std::string path = write(replaced(
      kScene,
      "    mesh: {box: {min: [0, -0.05, -0.05], max: [1, 0.05, 0.05], cells: [10, 2, 2]}}\n",
      "    mesh: meshes/missing.msh\n"));
  const dc::SceneSpec spec = dio::readSceneFile(path);
  try {
    dio::buildSimulation(spec, nullptr);
    FAIL() << "expected a MeshError";
  } catch (const dio::MeshError& e) {
    EXPECT_EQ(std::string(e.what()), path + ":8: bodies[0].mesh: cannot open mesh file '" +
                                         (directory_ / "meshes/missing.msh").string() +
                                         "': No such file or directory");
  }
}

// Whether a group selects nodes is known only with the mesh; the message still says where the
// group stands in the file (its own line, not its body's or the groups key's).
TEST_F(SceneFileOnDisk, GroupThatSelectsNoNodeNamesTheSceneFileLineAndKey) {
  const std::string path =
      write(replaced(kScene, "    loads:\n",
                     "    groups:\n"
                     "      tip: {box: {min: [0.999, -1, -1], max: [1.001, 1, 1]}}\n"
                     "      nowhere: {sphere: {center: [5, 5, 5], radius: 0.1}}\n"
                     "    loads:\n"));
  try {
    dio::buildSimulation(dio::readSceneFile(path), nullptr);
    FAIL() << "expected a SceneError";
  } catch (const dio::SceneError& e) {
    EXPECT_EQ(std::string(e.what()), path + ":14: bodies[0].groups.nowhere: selects no node");
  }
}

// A spec made in code has no file to point into: the key alone, as before.
TEST(SceneFile, SpecMadeInCodeErrorsNameTheKeyOnly) {
  dc::SceneSpec spec = dio::parseScene(kScene, "test.yaml", ".");
  spec.source = dc::SceneSource{};
  spec.bodies[0].fixed[1].node_numbers = {100000};
  EXPECT_THROW(
      {
        try {
          dio::buildSimulation(spec, nullptr);
        } catch (const dio::SceneError& e) {
          EXPECT_STREQ(e.what(), "bodies[0].fixed[1]: node 100000 is not a node of the mesh");
          throw;
        }
      },
      dio::SceneError);
}

namespace {

const std::string kScenes = DEFORMABLE_SIM_SOURCE_DIR "/test/data/scenes/";

std::string meshObstacleScene(const std::string& mesh) {
  return "effects: {contact: {friction: 0.3}}\n"
         "obstacles:\n"
         "  - {name: ramp, mesh: " +
         mesh +
         ", position: [0, 0, 1], rpy: [0, 0, 0]}\n"
         "bodies:\n"
         "  - {name: b, mesh: {box: {min: [0, 0, 0], max: [1, 1, 1], cells: [1, 1, 1]}}, "
         "material: {}}\n";
}

}  // namespace

TEST(SceneFile, MeshObstaclesAreReadRelativeToTheSceneFile) {
  const dc::SceneSpec spec = dio::readSceneFile(kScenes + "block_on_mesh_table.yaml");
  ASSERT_EQ(spec.obstacles.size(), 1u);
  const dc::PlacedShape& table = spec.obstacles[0];
  EXPECT_EQ(table.name, "table");
  ASSERT_EQ(table.shape.kind, dc::Shape::Kind::kMesh);
  ASSERT_TRUE(table.shape.mesh);
  EXPECT_TRUE(table.shape.mesh->closed());
  EXPECT_EQ(table.shape.mesh->mesh().triangles.size(), 12u);
  // Scaled to 1 x 1 x 0.1 m: 5 cm from its centre to its top.
  EXPECT_NEAR(dc::signedDistance(table.shape, {0.1, 0.2, 0.0}), -0.05, 1e-9);
  EXPECT_TRUE(table.pose.translation().isApprox(Eigen::Vector3d(0, 0, -0.05)));
}

// The node records a scene file's text and path (both empty for the built-in scene); a replay
// builds the scene again from them, meshes relative to where the file was.
TEST(SceneFile, ASceneIsBuiltAgainFromTheTextAndPathItWasReadFrom) {
  const std::string path = kScenes + "block_on_mesh_table.yaml";
  const dc::SceneSpec again = dio::sceneFromFileText(dio::readSceneText(path), path);
  ASSERT_EQ(again.obstacles.size(), 1u);
  ASSERT_TRUE(again.obstacles[0].shape.mesh);
  EXPECT_EQ(again.obstacles[0].shape.mesh->mesh().triangles.size(), 12u);
  const dc::SceneSpec builtin = dio::sceneFromFileText("", "");
  ASSERT_EQ(builtin.bodies.size(), 1u);
  EXPECT_EQ(builtin.bodies[0].name, dc::defaultScene().bodies[0].name);
  try {
    dio::sceneFromFileText("", "somewhere.yaml");  // an empty file is no scene
    ADD_FAILURE() << "an empty scene file was accepted";
  } catch (const dio::SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("somewhere.yaml", 0), 0u) << e.what();
  }
}

TEST(SceneFile, MeshObstacleErrorsNameTheFileLineAndKey) {
  const std::string meshes = DEFORMABLE_SIM_SOURCE_DIR "/test/data/meshes";
  auto error = [&](const std::string& mesh) {
    try {
      dio::parseScene(meshObstacleScene(mesh), "test.yaml", meshes);
    } catch (const dio::SceneError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(error("{file: cube.obj, scale: [2, 2, 2]}"), "accepted");
  EXPECT_EQ(error("{file: nowhere.stl}"),
            "test.yaml:3: obstacles[0].mesh.file: cannot open mesh "
            "file '" +
                meshes + "/nowhere.stl': no such file");
  EXPECT_EQ(error("{file: cube.obj, size: 2}"),
            "test.yaml:3: obstacles[0].mesh.size: unknown key (expected one of: file, scale)");
  EXPECT_EQ(error("{file: cube.obj, scale: [1, 0, 1]}"),
            "test.yaml:3: obstacles[0].mesh.scale: must not be 0");
  EXPECT_EQ(error("{scale: [1, 1, 1]}"), "test.yaml:3: obstacles[0].mesh.file: missing");
  const std::string empty = error("{file: no_triangles.obj}");
  EXPECT_NE(empty.find("test.yaml:3: obstacles[0].mesh.file: mesh file '"), std::string::npos)
      << empty;
  EXPECT_NE(empty.find("no_triangles.obj': holds no triangle"), std::string::npos) << empty;
}

// effects: {contact: {friction, bodies, self}}, and a body that turns them off for itself.
TEST(SceneFile, ContactBetweenBodiesAndWithItselfIsTurnedOnByTheSceneAndOffByABody) {
  std::string yaml = replaced(kScene, "effects: {gravity: [0, 0, -9.81],",
                              "effects: {contact: {friction: 0.3, bodies: true, self: false}, "
                              "gravity: [0, 0, -9.81],");
  yaml = replaced(yaml, "    model: fem\n", "    effects: {contact: {bodies: false}}\n");
  const dc::SceneSpec spec = dio::parseScene(yaml, "test.yaml", ".");
  ASSERT_TRUE(spec.contact.has_value());
  EXPECT_EQ(spec.contact->friction, 0.3);
  EXPECT_TRUE(spec.contact->bodies);
  EXPECT_FALSE(spec.contact->self);
  ASSERT_TRUE(spec.bodies[0].effects.has_value());
  EXPECT_EQ(spec.bodies[0].effects->contact_bodies, false);
  EXPECT_FALSE(spec.bodies[0].effects->contact_self.has_value());  // the scene's
  // Without the keys, contact is with obstacles only, as before.
  const dc::SceneSpec plain =
      dio::parseScene(replaced(kScene, "effects: {", "effects: {contact: {}, "), "t", ".");
  EXPECT_FALSE(plain.contact->bodies);
  EXPECT_FALSE(plain.contact->self);
  EXPECT_FALSE(plain.contact->one_problem);
  EXPECT_NE(errorOf(replaced(kScene, "effects: {", "effects: {contact: {self: 2}, ")), "");
  // All contact as one problem a step (doc/physics.md, "One problem a step").
  const dc::SceneSpec one = dio::parseScene(
      replaced(kScene, "effects: {", "effects: {contact: {one_problem: true}, "), "t", ".");
  EXPECT_TRUE(one.contact->one_problem);
  EXPECT_EQ(errorOf(replaced(kScene, "effects: {", "effects: {contact: {one_problem: 1.5}, ")),
            "test.yaml:3: effects.contact.one_problem: expected true or false");
}

TEST(SceneFile, ABodyHasItsOwnColourOrThePalettes) {
  const std::string coloured =
      replaced(kScene, "    model: fem\n", "    model: fem\n    colour: [0.2, 1, 0]\n");
  const dc::SceneSpec spec = dio::parseScene(coloured, "test.yaml", ".");
  ASSERT_TRUE(spec.bodies[0].colour.has_value());
  EXPECT_EQ(*spec.bodies[0].colour, Eigen::Vector3d(0.2, 1.0, 0.0));
  EXPECT_FALSE(dio::parseScene(kScene, "test.yaml", ".").bodies[0].colour.has_value());
  EXPECT_EQ(errorOf(replaced(coloured, "[0.2, 1, 0]", "[0.2, 1.5, 0]")),
            "test.yaml:10: bodies[0].colour[1]: must be in [0, 1]");
  EXPECT_EQ(errorOf(replaced(coloured, "[0.2, 1, 0]", "[0.2, 1, -0.1]")),
            "test.yaml:10: bodies[0].colour[2]: must be in [0, 1]");
  EXPECT_EQ(errorOf(replaced(coloured, "[0.2, 1, 0]", "[0.2, 1]")),
            "test.yaml:10: bodies[0].colour: expected [r, g, b] in [0, 1]");
  EXPECT_EQ(errorOf(replaced(coloured, "[0.2, 1, 0]", "[0.2, 1, 0, 1]")),
            "test.yaml:10: bodies[0].colour: expected [r, g, b] in [0, 1]");
  EXPECT_EQ(errorOf(replaced(coloured, "[0.2, 1, 0]", "red")),
            "test.yaml:10: bodies[0].colour: expected [r, g, b] in [0, 1]");
}

TEST(SceneFile, MeshObstaclesKeepTheirFileForViewers) {
  const std::string yaml = std::string(kScene) + R"(obstacles:
  - {name: table, mesh: {file: meshes/cube_binary.stl, scale: [1, 2, 0.1]}}
)";
  const std::string scene = replaced(yaml, "effects: {", "effects: {contact: {}, ");
  const std::string data = std::string(DEFORMABLE_SIM_SOURCE_DIR) + "/test/data";
  const dc::SceneSpec spec = dio::parseScene(scene, "test.yaml", data);
  ASSERT_EQ(spec.obstacles.size(), 1u);
  EXPECT_EQ(spec.obstacles[0].shape.mesh_uri, "file://" + data + "/meshes/cube_binary.stl");
  EXPECT_EQ(spec.obstacles[0].shape.mesh_scale, Eigen::Vector3d(1, 2, 0.1));
}

// material.law: the warped stiffness with the body's warping on (corotational) or off (linear),
// or Neo-Hookean; without it, the scene's effects.warping decides as before.
TEST(SceneFile, MaterialLawChoosesTheElasticModel) {
  const auto withLaw = [](const std::string& law) {
    return dio::parseScene(replaced(kScene, "material: {", "material: {law: " + law + ", "), "t",
                           ".");
  };
  const dc::SceneSpec plain = dio::parseScene(kScene, "t", ".");
  EXPECT_EQ(plain.bodies[0].material.law, dc::ElasticLaw::kWarpedStiffness);
  EXPECT_FALSE(plain.bodies[0].effects.has_value());
  const dc::SceneSpec neo = withLaw("neo_hookean");
  EXPECT_EQ(neo.bodies[0].material.law, dc::ElasticLaw::kNeoHookean);
  const dc::SceneSpec linear = withLaw("linear");
  EXPECT_EQ(linear.bodies[0].material.law, dc::ElasticLaw::kWarpedStiffness);
  ASSERT_TRUE(linear.bodies[0].effects.has_value());
  EXPECT_FALSE(linear.bodies[0].effects->warping);
  EXPECT_TRUE(linear.bodies[0].effects->gravity.has_value());  // the rest as the scene's
  const dc::SceneSpec corotational = withLaw("corotational");
  ASSERT_TRUE(corotational.bodies[0].effects.has_value());
  EXPECT_TRUE(corotational.bodies[0].effects->warping);
  // The Neo-Hookean scene builds and steps.
  dc::Simulation sim = dio::buildSimulation(neo, nullptr);
  std::vector<dc::StepReport> reports;
  for (int s = 0; s < 5; ++s) sim.step(reports);
  EXPECT_TRUE(sim.bodies()[0].stateIsFinite());
  EXPECT_GT(reports[0].solves, 0);
}

TEST(SceneFile, MaterialLawErrorsNameFileLineAndKey) {
  EXPECT_EQ(errorOf(replaced(kScene, "material: {", "material: {law: rubber, ")),
            "test.yaml:10: bodies[0].material.law: 'rubber' is not one of: corotational, linear, "
            "neo_hookean");
  EXPECT_EQ(errorOf(replaced(replaced(kScene, "material: {", "material: {law: neo_hookean, "),
                             "model: fem", "model: rigid")),
            "test.yaml:10: bodies[0].material.law: a material law is for a body of model: fem");
  EXPECT_EQ(errorOf(replaced(kScene, "material: {",
                             "effects: {warping: true}\n    material: {law: linear, ")),
            "test.yaml:11: bodies[0].material.law: contradicts the body's effects.warping: true");
}
