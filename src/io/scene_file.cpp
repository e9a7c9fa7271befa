#include "deformable_sim/io/scene_file.h"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/parameter_limits.h"
#include "deformable_sim/core/session/default_scene.h"
#include "deformable_sim/core/surface_bodies/voxelization.h"
#include "deformable_sim/io/mesh_reader.h"
#include "deformable_sim/io/surface_body_reader.h"
#include "deformable_sim/io/triangle_mesh_reader.h"
#include "deformable_sim/io/urdf_visual_mesh.h"

namespace deformable_sim::io {

namespace {

// Reads typed values out of YAML nodes; every error names the source, the line and the key.
class SceneParser {
 public:
  SceneParser(std::string source, std::string base_directory, ObstacleMeshLoader load_mesh)
      : source_(std::move(source)),
        base_directory_(std::move(base_directory)),
        load_mesh_(std::move(load_mesh)) {}

  core::SceneSpec parse(const YAML::Node& root) {
    core::SceneSpec scene;
    expectMap(root, "scene");
    checkKeys(root, "", {"dt", "effects", "solver", "static", "bodies", "obstacles", "urdf"});
    if (root["dt"]) scene.dt = positive(root["dt"], "dt");
    parseEffects(root["effects"], "effects", scene.effects);
    if (const YAML::Node effects = root["effects"]) {
      scene.contact = parseContact(effects["contact"]);
    }
    parseObstacles(root["obstacles"], scene.obstacles);
    parseUrdf(root["urdf"], scene);
    if ((!scene.obstacles.empty() || !scene.urdf_links.empty()) && !scene.contact) {
      fail(root, "effects.contact",
           "obstacles are given but the contact effect is off: add effects: {contact: {}}");
    }
    parseSolver(root["solver"], scene.solver);
    parseStatic(root["static"], scene.statics);
    parseBodies(root, scene);
    scene.source.file = source_;
    scene.source.lines = std::move(lines_);
    return scene;
  }

 private:
  [[noreturn]] void fail(const YAML::Node& node, const std::string& key,
                         const std::string& message) const {
    std::ostringstream text;
    text << source_;
    if (node.IsDefined() && node.Mark().line >= 0) text << ":" << node.Mark().line + 1;
    text << ": " << (key.empty() ? "scene" : key) << ": " << message;
    throw SceneError(text.str());
  }

  static std::string join(const std::string& parent, const std::string& child) {
    return parent.empty() ? child : parent + "." + child;
  }

  void expectMap(const YAML::Node& node, const std::string& key) const {
    if (!node.IsMap()) fail(node, key, "expected a map of keys");
  }

  // A map's key as text. YAML allows any node as a key ({[1, 2]: x}, a null); a scene's keys are
  // names, and as<std::string>() would throw YAML's own exception for the others.
  std::string keyName(const YAML::Node& key_node, const std::string& key) const {
    if (!key_node.IsScalar()) fail(key_node, key, "expected a key name, found a list, map or null");
    return key_node.Scalar();
  }

  void checkKeys(const YAML::Node& node, const std::string& key,
                 const std::set<std::string>& allowed) const {
    for (const auto& entry : node) {
      const std::string name = keyName(entry.first, key);
      if (allowed.count(name) == 0) {
        std::string expected;
        for (const std::string& a : allowed) expected += (expected.empty() ? "" : ", ") + a;
        fail(entry.first, join(key, name), "unknown key (expected one of: " + expected + ")");
      }
    }
  }

  double number(const YAML::Node& node, const std::string& key) const {
    double value = 0.0;
    if (!node.IsScalar() || !YAML::convert<double>::decode(node, value)) {
      fail(node, key, "expected a number");
    }
    if (!std::isfinite(value)) fail(node, key, "must be finite");
    return value;
  }

  double positive(const YAML::Node& node, const std::string& key) const {
    const double value = number(node, key);
    if (!(value > 0.0)) fail(node, key, "must be > 0");
    return value;
  }

  double nonNegative(const YAML::Node& node, const std::string& key) const {
    const double value = number(node, key);
    if (!(value >= 0.0)) fail(node, key, "must be >= 0");
    return value;
  }

  // Fails unless `value` is one that `parameter` may be (core/parameter_limits.h).
  void within(const YAML::Node& node, const std::string& key, core::Parameter parameter,
              double value) const {
    const std::string problem = core::parameterProblem(parameter, value);
    if (!problem.empty()) fail(node, key, problem);
  }

  double parameter(const YAML::Node& node, const std::string& key,
                   core::Parameter parameter) const {
    const double value = number(node, key);
    within(node, key, parameter, value);
    return value;
  }

  long integer(const YAML::Node& node, const std::string& key) const {
    long value = 0;
    if (!node.IsScalar() || !YAML::convert<long>::decode(node, value)) {
      fail(node, key, "expected an integer");
    }
    return value;
  }

  bool boolean(const YAML::Node& node, const std::string& key) const {
    bool value = false;
    if (!node.IsScalar() || !YAML::convert<bool>::decode(node, value)) {
      fail(node, key, "expected true or false");
    }
    return value;
  }

  std::string text(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar() || node.Scalar().empty()) fail(node, key, "expected a non-empty string");
    return node.Scalar();
  }

  Eigen::Vector3d vector3(const YAML::Node& node, const std::string& key) const {
    if (!node.IsSequence() || node.size() != 3) fail(node, key, "expected a list of 3 numbers");
    return {number(node[0], key + "[0]"), number(node[1], key + "[1]"),
            number(node[2], key + "[2]")};
  }

  // `false` (or `off`) for an optional effect: a body turns off what its scene enables.
  bool switchedOff(const YAML::Node& node) const {
    bool value = true;
    return node.IsScalar() && YAML::convert<bool>::decode(node, value) && !value;
  }

  // Keeps where `key` stands in the file, for the errors found once the spec is built.
  void remember(const std::string& key, const YAML::Node& node) {
    if (node.IsDefined() && node.Mark().line >= 0) lines_[key] = node.Mark().line + 1;
  }

  // One of `choices` by its name in the file.
  template <typename Value>
  Value choice(const YAML::Node& node, const std::string& key,
               const std::vector<std::pair<std::string, Value>>& choices) const {
    const std::string name = text(node, key);
    std::string names;
    for (const auto& [choice_name, value] : choices) {
      if (choice_name == name) return value;
      names += (names.empty() ? "" : ", ") + choice_name;
    }
    fail(node, key, "'" + name + "' is not one of: " + names);
  }

  // An integer of at least `minimum`.
  int atLeast(const YAML::Node& node, const std::string& key, int minimum) const {
    const int value = static_cast<int>(integer(node, key));
    if (value < minimum) fail(node, key, "must be >= " + std::to_string(minimum));
    return value;
  }

  std::optional<core::ContactSettings> parseContact(const YAML::Node& contact) const {
    if (!contact) return std::nullopt;
    expectMap(contact, "effects.contact");
    checkKeys(contact, "effects.contact", {"friction", "bodies", "self", "one_problem"});
    core::ContactSettings settings;
    if (contact["friction"]) {
      settings.friction = nonNegative(contact["friction"], "effects.contact.friction");
    }
    if (contact["bodies"]) settings.bodies = boolean(contact["bodies"], "effects.contact.bodies");
    if (contact["self"]) settings.self = boolean(contact["self"], "effects.contact.self");
    if (contact["one_problem"]) {
      settings.one_problem = boolean(contact["one_problem"], "effects.contact.one_problem");
    }
    return settings;
  }

  // A body's say on contact between bodies and with itself (bodies[i].effects.contact); the
  // friction and the obstacles are the scene's.
  void parseBodyContact(const YAML::Node& contact, const std::string& key,
                        core::BodyEffects& effects) const {
    expectMap(contact, key);
    checkKeys(contact, key, {"bodies", "self"});
    if (contact["bodies"]) effects.contact_bodies = boolean(contact["bodies"], key + ".bodies");
    if (contact["self"]) effects.contact_self = boolean(contact["self"], key + ".self");
  }

  void parseObstacles(const YAML::Node& obstacles, std::vector<core::PlacedShape>& shapes) const {
    if (!obstacles) return;
    if (!obstacles.IsSequence()) fail(obstacles, "obstacles", "expected a list of obstacles");
    for (size_t k = 0; k < obstacles.size(); ++k) {
      shapes.push_back(parseObstacle(obstacles[k], sceneObstacleKey(static_cast<int>(k))));
    }
  }

  void parseUrdf(const YAML::Node& urdf, core::SceneSpec& scene) const {
    if (!urdf) return;
    expectMap(urdf, "urdf");
    checkKeys(urdf, "urdf", {"links", "file"});
    if (urdf["file"]) scene.urdf_file = resolvedPath(urdf["file"], "urdf.file");
    const YAML::Node links = urdf["links"];
    if (!links || !links.IsSequence() || links.size() == 0) {
      fail(links ? links : urdf, "urdf.links", "expected a non-empty list of link names");
    }
    for (size_t k = 0; k < links.size(); ++k) {
      scene.urdf_links.push_back(text(links[k], "urdf.links[" + std::to_string(k) + "]"));
    }
  }

  // A file path, relative to the scene file's directory unless absolute.
  std::string resolvedPath(const YAML::Node& node, const std::string& key) const {
    std::filesystem::path path = text(node, key);
    if (path.is_relative()) path = std::filesystem::path(base_directory_) / path;
    return path.lexically_normal().string();
  }

  void parseBodies(const YAML::Node& root, core::SceneSpec& scene) {
    const YAML::Node bodies = root["bodies"];
    if (!bodies) fail(root, "bodies", "missing: a scene needs at least one body");
    if (!bodies.IsSequence() || bodies.size() == 0) {
      fail(bodies, "bodies", "expected a non-empty list of bodies");
    }
    std::set<std::string> names;
    for (size_t b = 0; b < bodies.size(); ++b) {
      const std::string key = "bodies[" + std::to_string(b) + "]";
      scene.bodies.push_back(parseBody(bodies[b], key, scene.effects));
      if (!names.insert(scene.bodies.back().name).second) {
        fail(bodies[b], key + ".name", "'" + scene.bodies.back().name + "' is used twice");
      }
    }
  }

  // The scene's effects (key "effects"), or a body's ("bodies[i].effects"), which start from the
  // scene's and change what they name.
  void parseEffects(const YAML::Node& node, const std::string& key,
                    core::BodyEffects& effects) const {
    if (!node) return;
    expectMap(node, key);
    const bool scene = key == "effects";
    std::set<std::string> keys = {"gravity",    "warping",          "damping",
                                  "plasticity", "stress_colouring", "reactions"};
    keys.insert("contact");
    checkKeys(node, key, keys);
    if (!scene && node["contact"]) parseBodyContact(node["contact"], key + ".contact", effects);
    if (node["stress_colouring"]) {
      effects.stress_colouring = boolean(node["stress_colouring"], key + ".stress_colouring");
    }
    if (node["reactions"]) effects.reactions = boolean(node["reactions"], key + ".reactions");
    if (node["warping"]) effects.warping = boolean(node["warping"], key + ".warping");
    if (const YAML::Node gravity = node["gravity"]) {
      if (switchedOff(gravity)) {
        effects.gravity.reset();
      } else {
        effects.gravity = vector3(gravity, key + ".gravity");
      }
    }
    if (const YAML::Node damping = node["damping"]) {
      if (switchedOff(damping)) {
        effects.damping.reset();
      } else {
        expectMap(damping, key + ".damping");
        checkKeys(damping, key + ".damping", {"mass", "stiffness"});
        core::RayleighDamping rayleigh;
        if (damping["mass"]) {
          rayleigh.mass =
              parameter(damping["mass"], key + ".damping.mass", core::Parameter::kDampingMass);
        }
        if (damping["stiffness"]) {
          rayleigh.stiffness = parameter(damping["stiffness"], key + ".damping.stiffness",
                                         core::Parameter::kDampingStiffness);
        }
        effects.damping = rayleigh;
      }
    }
    if (const YAML::Node plasticity = node["plasticity"]) {
      if (switchedOff(plasticity)) {
        effects.plasticity.reset();
      } else {
        const std::string item = key + ".plasticity";
        expectMap(plasticity, item);
        checkKeys(plasticity, item, {"yield", "creep", "max_strain"});
        core::PlasticitySettings settings;
        if (plasticity["yield"]) settings.yield = nonNegative(plasticity["yield"], item + ".yield");
        if (plasticity["creep"]) settings.creep = nonNegative(plasticity["creep"], item + ".creep");
        if (plasticity["max_strain"]) {
          settings.max_strain = number(plasticity["max_strain"], item + ".max_strain");
          if (!(settings.max_strain > 0.0)) {
            fail(plasticity["max_strain"], item + ".max_strain", "must be > 0");
          }
        }
        effects.plasticity = settings;
      }
    }
  }

  void parseSolver(const YAML::Node& node, core::SolverSettings& solver) const {
    if (!node) return;
    expectMap(node, "solver");
    checkKeys(node, "solver",
              {"method", "preconditioner", "tolerance", "max_iterations", "coarse_refresh_interval",
               "threads", "warm_start", "previous_solutions", "max_rotation_updates"});
    using Settings = core::SolverSettings;
    if (node["method"]) {
      solver.method = choice<Settings::Method>(
          node["method"], "solver.method",
          {{"cg", Settings::Method::kConjugateGradient}, {"direct", Settings::Method::kDirect}});
    }
    if (node["preconditioner"]) {
      solver.preconditioner = choice<Settings::Preconditioner>(
          node["preconditioner"], "solver.preconditioner",
          {{"two_level", Settings::Preconditioner::kTwoLevel},
           {"block_jacobi", Settings::Preconditioner::kBlockJacobi},
           {"factorization", Settings::Preconditioner::kFactorization}});
    }
    if (node["warm_start"]) {
      solver.warm_start =
          choice<Settings::WarmStart>(node["warm_start"], "solver.warm_start",
                                      {{"projected", Settings::WarmStart::kProjected},
                                       {"extrapolated", Settings::WarmStart::kExtrapolated},
                                       {"last_velocity", Settings::WarmStart::kLastVelocity}});
    }
    parseSolverLimits(node, solver);
  }

  void parseSolverLimits(const YAML::Node& node, core::SolverSettings& solver) const {
    if (node["previous_solutions"]) {
      solver.previous_solutions =
          static_cast<int>(integer(node["previous_solutions"], "solver.previous_solutions"));
      if (solver.previous_solutions < 1 || solver.previous_solutions > 256)
        fail(node["previous_solutions"], "solver.previous_solutions", "must be in 1 .. 256");
    }
    if (node["coarse_refresh_interval"]) {
      solver.coarse_refresh_interval =
          atLeast(node["coarse_refresh_interval"], "solver.coarse_refresh_interval", 1);
    }
    if (node["threads"]) solver.threads = atLeast(node["threads"], "solver.threads", 1);
    if (node["max_rotation_updates"]) {
      solver.max_rotation_updates =
          atLeast(node["max_rotation_updates"], "solver.max_rotation_updates", 0);
    }
    if (node["tolerance"]) {
      solver.tolerance =
          parameter(node["tolerance"], "solver.tolerance", core::Parameter::kSolverTolerance);
    }
    if (node["max_iterations"]) {
      const long iterations = integer(node["max_iterations"], "solver.max_iterations");
      within(node["max_iterations"], "solver.max_iterations", core::Parameter::kSolverMaxIterations,
             static_cast<double>(iterations));
      solver.max_iterations = static_cast<int>(iterations);
    }
  }

  void parseStatic(const YAML::Node& node, core::StaticSettings& statics) const {
    if (!node) return;
    expectMap(node, "static");
    checkKeys(node, "static", {"load_steps", "max_iterations", "tolerance"});
    if (node["load_steps"]) {
      statics.load_steps = atLeast(node["load_steps"], "static.load_steps", 1);
    }
    if (node["max_iterations"]) {
      statics.max_iterations = atLeast(node["max_iterations"], "static.max_iterations", 1);
    }
    if (node["tolerance"]) statics.tolerance = positive(node["tolerance"], "static.tolerance");
  }

  core::BodySpec parseBody(const YAML::Node& node, const std::string& key,
                           const core::BodyEffects& scene_effects) {
    expectMap(node, key);
    checkKeys(node, key,
              {"name", "mesh", "model", "material", "effects", "fixed", "loads", "groups",
               "wrench_radius", "velocity", "colour"});
    remember(key, node);
    core::BodySpec body;
    if (!node["name"]) fail(node, key + ".name", "missing");
    body.name = text(node["name"], key + ".name");
    parseMesh(node["mesh"], node, key + ".mesh", body);
    remember(key + ".mesh", node["mesh"]);
    if (node["model"]) {
      body.model = choice<core::BodyModel>(node["model"], key + ".model",
                                           {{"fem", core::BodyModel::kFiniteElement},
                                            {"pseudo_rigid", core::BodyModel::kPseudoRigid},
                                            {"rigid", core::BodyModel::kRigid}});
    }
    if (const YAML::Node effects = node["effects"]) {
      body.effects = scene_effects;
      // The scene's plasticity is for its finite-element bodies; a body names it to get it.
      if (body.model != core::BodyModel::kFiniteElement) body.effects->plasticity.reset();
      parseEffects(effects, key + ".effects", *body.effects);
    }
    if (!node["material"]) fail(node, key + ".material", "missing");
    parseMaterial(node["material"], key + ".material", body.material);
    if (const YAML::Node law = node["material"]["law"]) {
      parseLaw(law, key + ".material.law", node["effects"], scene_effects, body);
    }
    parseFixed(node["fixed"], key + ".fixed", body.fixed);
    parseGroups(node["groups"], key + ".groups", body.groups);
    if (node["wrench_radius"]) {
      body.wrench_radius = nonNegative(node["wrench_radius"], key + ".wrench_radius");
      remember(key + ".wrench_radius", node["wrench_radius"]);
    }
    if (node["velocity"]) {
      body.velocity = vector3(node["velocity"], key + ".velocity");
      remember(key + ".velocity", node["velocity"]);
    }
    if (node["colour"]) body.colour = colour(node["colour"], key + ".colour");
    parseLoads(node["loads"], key + ".loads", body.loads);
    return body;
  }

  // [r, g, b], each in [0, 1].
  Eigen::Vector3d colour(const YAML::Node& node, const std::string& key) const {
    if (!node.IsSequence() || node.size() != 3) fail(node, key, "expected [r, g, b] in [0, 1]");
    Eigen::Vector3d rgb;
    for (int k = 0; k < 3; ++k) {
      const std::string item = key + "[" + std::to_string(k) + "]";
      rgb[k] = number(node[k], item);
      if (!(rgb[k] >= 0.0 && rgb[k] <= 1.0)) fail(node[k], item, "must be in [0, 1]");
    }
    return rgb;
  }

  void parseFixed(const YAML::Node& fixed, const std::string& key,
                  std::vector<core::NodeSelection>& selections) {
    if (!fixed) return;
    if (!fixed.IsSequence()) fail(fixed, key, "expected a list of selections");
    for (size_t k = 0; k < fixed.size(); ++k) {
      const std::string item = key + "[" + std::to_string(k) + "]";
      expectMap(fixed[k], item);
      checkKeys(fixed[k], item, {"nodes", "box", "sphere"});
      selections.push_back(parseSelection(fixed[k], item));
      remember(item, fixed[k]);
    }
  }

  void parseGroups(const YAML::Node& groups, const std::string& key,
                   std::map<std::string, core::NodeSelection>& selections) {
    if (!groups) return;
    expectMap(groups, key);
    for (const auto& entry : groups) {
      const std::string name = keyName(entry.first, key);
      const std::string item = key + "." + name;
      expectMap(entry.second, item);
      checkKeys(entry.second, item, {"nodes", "box", "sphere"});
      selections[name] = parseSelection(entry.second, item);
      remember(item, entry.second);
    }
  }

  void parseLoads(const YAML::Node& loads, const std::string& key,
                  std::vector<core::LoadSpec>& specs) {
    if (!loads) return;
    if (!loads.IsSequence()) fail(loads, key, "expected a list of loads");
    for (size_t k = 0; k < loads.size(); ++k) {
      const std::string item = key + "[" + std::to_string(k) + "]";
      specs.push_back(parseLoad(loads[k], item));
      remember(item, loads[k]);
    }
  }

  void parseMesh(const YAML::Node& node, const YAML::Node& parent, const std::string& key,
                 core::BodySpec& body) const {
    if (!node) {
      fail(parent, key, "missing: a mesh file, {box: {min, max, cells}} or {surface: file, ..}");
    }
    if (node.IsScalar()) {
      body.mesh = resolvedPath(node, key);
      return;
    }
    expectMap(node, key);
    checkKeys(
        node, key,
        {"box", "surface", "urdf_link", "cell_size", "cells", "max_cells", "position", "rpy"});
    if (node["surface"] || node["urdf_link"]) {
      body.surface_mesh = parseSurfaceMesh(node, key);
      return;
    }
    const YAML::Node box = node["box"];
    if (!box) fail(node, key + ".box", "missing (or give surface: file or urdf_link: name)");
    for (const char* other : {"cell_size", "cells", "max_cells", "position", "rpy"}) {
      if (node[other]) fail(node[other], key + "." + other, "only with surface or urdf_link");
    }
    expectMap(box, key + ".box");
    checkKeys(box, key + ".box", {"min", "max", "cells", "element"});
    for (const char* required : {"min", "max", "cells"}) {
      if (!box[required]) fail(box, key + ".box." + required, "missing");
    }
    core::BoxMeshSpec spec;
    spec.min = vector3(box["min"], key + ".box.min");
    spec.max = vector3(box["max"], key + ".box.max");
    const Eigen::Vector3d cells = vector3(box["cells"], key + ".box.cells");
    if (!(spec.min.array() < spec.max.array()).all()) {
      fail(box, key + ".box", "min must be below max on every axis");
    }
    if ((cells.array() < 1.0).any() || (cells.array() != cells.array().round()).any()) {
      fail(box["cells"], key + ".box.cells", "expected three whole numbers >= 1");
    }
    // Checked before the conversion to int, which would overflow (undefined) for 1e10.
    if (cells.prod() > static_cast<double>(core::kMaxBoxMeshCells)) {
      fail(box["cells"], key + ".box.cells",
           "more than " + std::to_string(core::kMaxBoxMeshCells) + " cells in all");
    }
    spec.cells = cells.cast<int>();
    if (box["element"]) {
      spec.element = choice<core::BoxElement>(box["element"], key + ".box.element",
                                              {{"tetrahedron", core::BoxElement::kTetrahedron},
                                               {"hexahedron", core::BoxElement::kHexahedron},
                                               {"wedge", core::BoxElement::kWedge},
                                               {"pyramid", core::BoxElement::kPyramid}});
    }
    body.box_mesh = spec;
  }

  // A package:// URI as it is (readMeshes resolves it, given a resolver); a path or file:// URI
  // relative to the scene file's directory unless absolute.
  std::string surfacePath(const YAML::Node& node, const std::string& key) const {
    const std::string uri = text(node, key);
    if (uri.rfind("package://", 0) == 0) return uri;
    std::filesystem::path path;
    try {
      path = resolveMeshUri(uri);
    } catch (const TriangleMeshError& e) {
      fail(node, key, e.what());
    }
    if (path.is_relative()) path = std::filesystem::path(base_directory_) / path;
    return path.lexically_normal().string();
  }

  // {surface: part.stl, cell_size: 0.01} or {urdf_link: name, cells: 20}: the body's grid is
  // made from the surface when the meshes are read.
  core::SurfaceMeshSpec parseSurfaceMesh(const YAML::Node& node, const std::string& key) const {
    if (node["box"]) fail(node, key, "give one of box, surface and urdf_link");
    if (node["surface"] && node["urdf_link"]) fail(node, key, "give one of surface and urdf_link");
    if (!node["cell_size"] == !node["cells"]) {
      fail(node, key, "give one of cell_size (m) and cells (along the longest side)");
    }
    core::SurfaceMeshSpec spec;
    if (node["surface"]) {
      spec.file = surfacePath(node["surface"], key + ".surface");
    } else {
      spec.urdf_link = text(node["urdf_link"], key + ".urdf_link");
    }
    if (node["cell_size"]) spec.voxels.cell_size = positive(node["cell_size"], key + ".cell_size");
    if (node["cells"]) {
      spec.voxels.longest_side_cells = atLeast(node["cells"], key + ".cells", 1);
    }
    if (node["max_cells"]) {  // up to what a mesh's int indices number
      spec.voxels.max_cells = integer(node["max_cells"], key + ".max_cells");
      if (spec.voxels.max_cells < 1) fail(node["max_cells"], key + ".max_cells", "must be >= 1");
      if (spec.voxels.max_cells > core::kMostGridCells) {
        fail(node["max_cells"], key + ".max_cells",
             "must be <= " + std::to_string(core::kMostGridCells) +
                 " (a mesh numbers its cells and nodes by int)");
      }
    }
    spec.pose = pose(node, key);
    return spec;
  }

  void parseMaterial(const YAML::Node& node, const std::string& key,
                     core::LinearElasticMaterial& material) const {
    expectMap(node, key);
    checkKeys(node, key, {"law", "youngs_modulus", "poisson_ratio", "density"});
    const auto read = [&](const char* name, core::Parameter p, double& value) {
      if (node[name]) value = parameter(node[name], key + "." + name, p);
    };
    read("youngs_modulus", core::Parameter::kYoungsModulus, material.youngs_modulus);
    read("poisson_ratio", core::Parameter::kPoissonRatio, material.poisson_ratio);
    read("density", core::Parameter::kDensity, material.density);
  }

  // material.law: corotational and linear are the warped stiffness with the body's warping on
  // and off (the default follows effects.warping); neo_hookean is for finite elements.
  void parseLaw(const YAML::Node& node, const std::string& key, const YAML::Node& body_effects,
                const core::BodyEffects& scene_effects, core::BodySpec& body) const {
    enum class Law { kCorotational, kLinear, kNeoHookean };
    const Law law = choice<Law>(node, key,
                                {{"corotational", Law::kCorotational},
                                 {"linear", Law::kLinear},
                                 {"neo_hookean", Law::kNeoHookean}});
    if (body.model != core::BodyModel::kFiniteElement) {
      fail(node, key, "a material law is for a body of model: fem");
    }
    if (law == Law::kNeoHookean) {
      body.material.law = core::ElasticLaw::kNeoHookean;
      return;
    }
    const bool warping = law == Law::kCorotational;
    if (body_effects && body_effects["warping"] && body.effects->warping != warping) {
      fail(node, key,
           std::string("contradicts the body's effects.warping: ") + (warping ? "false" : "true"));
    }
    if (!body.effects) body.effects = scene_effects;
    body.effects->warping = warping;
  }

  // A map with exactly one of nodes / box / sphere (other keys are checked by the caller).
  core::NodeSelection parseSelection(const YAML::Node& node, const std::string& key) const {
    core::NodeSelection selection;
    const int kinds = (node["nodes"] ? 1 : 0) + (node["box"] ? 1 : 0) + (node["sphere"] ? 1 : 0);
    if (kinds != 1) fail(node, key, "expected exactly one of: nodes, box, sphere");
    if (const YAML::Node nodes = node["nodes"]) {
      if (!nodes.IsSequence() || nodes.size() == 0) {
        fail(nodes, key + ".nodes", "expected a non-empty list of node numbers");
      }
      selection.kind = core::NodeSelection::Kind::kNodes;
      for (size_t i = 0; i < nodes.size(); ++i) {
        selection.node_numbers.push_back(
            integer(nodes[i], key + ".nodes[" + std::to_string(i) + "]"));
      }
    } else if (const YAML::Node box = node["box"]) {
      expectMap(box, key + ".box");
      checkKeys(box, key + ".box", {"min", "max"});
      if (!box["min"] || !box["max"]) fail(box, key + ".box", "needs min and max");
      selection.kind = core::NodeSelection::Kind::kBox;
      selection.box.min = vector3(box["min"], key + ".box.min");
      selection.box.max = vector3(box["max"], key + ".box.max");
      if ((selection.box.min.array() > selection.box.max.array()).any()) {
        fail(box, key + ".box", "min must not exceed max on any axis");
      }
    } else {
      const YAML::Node sphere = node["sphere"];
      expectMap(sphere, key + ".sphere");
      checkKeys(sphere, key + ".sphere", {"center", "radius"});
      if (!sphere["center"] || !sphere["radius"])
        fail(sphere, key + ".sphere", "needs center and radius");
      selection.kind = core::NodeSelection::Kind::kSphere;
      selection.sphere.center = vector3(sphere["center"], key + ".sphere.center");
      selection.sphere.radius = nonNegative(sphere["radius"], key + ".sphere.radius");
    }
    return selection;
  }

  core::PlacedShape parseObstacle(const YAML::Node& node, const std::string& key) const {
    expectMap(node, key);
    checkKeys(node, key, {"name", "box", "sphere", "cylinder", "mesh", "position", "rpy"});
    core::PlacedShape obstacle;
    obstacle.name = node["name"] ? text(node["name"], key + ".name") : key;
    const int kinds = (node["box"] ? 1 : 0) + (node["sphere"] ? 1 : 0) +
                      (node["cylinder"] ? 1 : 0) + (node["mesh"] ? 1 : 0);
    if (kinds != 1) fail(node, key, "expected exactly one of: box, sphere, cylinder, mesh");
    obstacle.shape = node["mesh"] ? parseMeshShape(node["mesh"], key) : parsePrimitive(node, key);
    try {
      core::validate(obstacle.shape, key);
    } catch (const std::invalid_argument& e) {
      fail(node, key, e.what());
    }
    obstacle.pose = pose(node, key);
    return obstacle;
  }

  // The optional keys position (m) and rpy (rad, roll-pitch-yaw about fixed x, y, z) of a map.
  Eigen::Isometry3d pose(const YAML::Node& node, const std::string& key) const {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    if (node["position"]) pose.translation() = vector3(node["position"], key + ".position");
    if (node["rpy"]) {
      const Eigen::Vector3d rpy = vector3(node["rpy"], key + ".rpy");
      pose.linear() = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                       Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                       Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                          .toRotationMatrix();
    }
    return pose;
  }

  // The box, sphere or cylinder of an obstacle entry.
  core::Shape parsePrimitive(const YAML::Node& node, const std::string& key) const {
    core::Shape shape;
    if (const YAML::Node box = node["box"]) {
      expectMap(box, key + ".box");
      checkKeys(box, key + ".box", {"size"});
      if (!box["size"]) fail(box, key + ".box.size", "missing");
      shape.kind = core::Shape::Kind::kBox;
      shape.size = vector3(box["size"], key + ".box.size");
    } else if (const YAML::Node sphere = node["sphere"]) {
      expectMap(sphere, key + ".sphere");
      checkKeys(sphere, key + ".sphere", {"radius"});
      if (!sphere["radius"]) fail(sphere, key + ".sphere.radius", "missing");
      shape.kind = core::Shape::Kind::kSphere;
      shape.radius = positive(sphere["radius"], key + ".sphere.radius");
    } else {
      const YAML::Node cylinder = node["cylinder"];
      expectMap(cylinder, key + ".cylinder");
      checkKeys(cylinder, key + ".cylinder", {"radius", "length"});
      if (!cylinder["radius"] || !cylinder["length"]) {
        fail(cylinder, key + ".cylinder", "needs radius and length");
      }
      shape.kind = core::Shape::Kind::kCylinder;
      shape.radius = positive(cylinder["radius"], key + ".cylinder.radius");
      shape.length = positive(cylinder["length"], key + ".cylinder.length");
    }
    return shape;
  }

  // {file: ramp.stl, scale: [1, 1, 1]}: read here, so that a bad file is reported at its line.
  core::Shape parseMeshShape(const YAML::Node& node, const std::string& obstacle_key) const {
    const std::string key = obstacle_key + ".mesh";
    expectMap(node, key);
    checkKeys(node, key, {"file", "scale"});
    if (!node["file"]) fail(node, key + ".file", "missing");
    Eigen::Vector3d scale = Eigen::Vector3d::Ones();
    if (node["scale"]) {
      scale = vector3(node["scale"], key + ".scale");
      if ((scale.array() == 0.0).any()) fail(node["scale"], key + ".scale", "must not be 0");
    }
    core::Shape shape;
    shape.kind = core::Shape::Kind::kMesh;
    try {
      const std::string uri = text(node["file"], key + ".file");
      std::filesystem::path file = resolveMeshUri(uri);
      if (file.is_relative()) file = std::filesystem::path(base_directory_) / file;
      const std::string name = file.lexically_normal().string();
      shape.mesh_uri = meshResourceUri(uri, name);
      shape.mesh_scale = scale;
      try {
        shape.mesh =
            load_mesh_
                ? load_mesh_(obstacle_key, name, scale)
                : std::make_shared<const core::TriangleMeshShape>(readTriangleMesh(name, scale));
      } catch (const std::invalid_argument& e) {
        throw TriangleMeshError("mesh file '" + name + "': " + e.what());
      }
    } catch (const TriangleMeshError& e) {
      fail(node["file"], key + ".file", e.what());
    }
    return shape;
  }

  core::LoadSpec parseLoad(const YAML::Node& node, const std::string& key) const {
    expectMap(node, key);
    checkKeys(node, key, {"nodes", "box", "sphere", "traction", "total_force", "wrench"});
    core::LoadSpec load;
    load.where = parseSelection(node, key);
    const int kinds =
        (node["traction"] ? 1 : 0) + (node["total_force"] ? 1 : 0) + (node["wrench"] ? 1 : 0);
    if (kinds > 1) fail(node, key, "give one of traction, total_force or wrench");
    if (const YAML::Node wrench = node["wrench"]) {
      expectMap(wrench, key + ".wrench");
      checkKeys(wrench, key + ".wrench", {"force", "torque"});
      load.kind = core::LoadSpec::Kind::kWrench;
      if (wrench["force"]) load.value = vector3(wrench["force"], key + ".wrench.force");
      if (wrench["torque"]) load.torque = vector3(wrench["torque"], key + ".wrench.torque");
      return load;
    }
    if (node["traction"]) {
      load.kind = core::LoadSpec::Kind::kTraction;
      load.value = vector3(node["traction"], key + ".traction");
    } else if (node["total_force"]) {
      load.kind = core::LoadSpec::Kind::kTotalForce;
      load.value = vector3(node["total_force"], key + ".total_force");
    } else {
      fail(node, key, "needs traction (Pa), total_force (N) or wrench {force (N), torque (N m)}");
    }
    return load;
  }

  std::string source_;
  std::string base_directory_;
  ObstacleMeshLoader load_mesh_;      // empty: from the file
  std::map<std::string, int> lines_;  // see core::SceneSource::lines
};

}  // namespace

std::string sceneObstacleKey(int index) { return "obstacles[" + std::to_string(index) + "]"; }

core::SceneSpec parseScene(const std::string& yaml_text, const std::string& source,
                           const std::string& base_directory, const ObstacleMeshLoader& load_mesh) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw SceneError(source + ":" + std::to_string(e.mark.line + 1) + ": not valid YAML: " + e.msg);
  }
  return SceneParser(source, base_directory, load_mesh).parse(root);
}

core::SceneSpec readSceneFile(const std::string& path) {
  return sceneFromFileText(readSceneText(path), path);
}

std::string readSceneText(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw SceneError(path + ": cannot open the scene file");
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

core::SceneSpec sceneFromFileText(const std::string& yaml_text, const std::string& path,
                                  const ObstacleMeshLoader& load_mesh) {
  if (yaml_text.empty() && path.empty()) return core::defaultScene();
  const std::string directory = std::filesystem::path(path).parent_path().string();
  return parseScene(yaml_text, path.empty() ? "scene" : path, directory.empty() ? "." : directory,
                    load_mesh);
}

namespace {

// "file:line: " of `key` in the scene file, or of the nearest enclosing key it kept the line of
// ("bodies[0]" for "bodies[0].wrench_radius"); "" for a scene made in code.
std::string whereInScene(const core::SceneSource& source, std::string key) {
  if (source.file.empty()) return "";
  while (!key.empty()) {
    const auto line = source.lines.find(key);
    if (line != source.lines.end()) return source.file + ":" + std::to_string(line->second) + ": ";
    const size_t parent_end = key.find_last_of(".[");
    key.resize(parent_end == std::string::npos ? 0 : parent_end);
  }
  return source.file + ": ";
}

}  // namespace

std::string locatedMessage(const core::SceneSpec& spec, const core::SpecError& error) {
  return whereInScene(spec.source, error.key()) + error.what();
}

namespace {

// The surface of a body from `mesh: {surface: ..}` or `{urdf_link: ..}`, voxelized and embedded.
// Throws TriangleMeshError, UrdfError or std::runtime_error.
core::SurfaceBody readSurfaceBodyOf(const core::SceneSpec& spec, const core::SurfaceMeshSpec& body,
                                    const SurfaceSources& sources,
                                    std::vector<std::string>* warnings) {
  if (body.urdf_link.empty()) {
    return readSurfaceBody(resolveMeshUri(body.file, sources.resolver), body.voxels, warnings,
                           body.pose);
  }
  std::string xml = sources.robot_description, directory;
  if (xml.empty()) {
    if (spec.urdf_file.empty()) {
      throw UrdfError("urdf_link '" + body.urdf_link +
                      "' needs the robot description: give urdf: {file: robot.urdf} in the scene");
    }
    std::ifstream in(spec.urdf_file);
    if (!in) throw UrdfError("cannot read the robot description '" + spec.urdf_file + "'");
    std::stringstream text;
    text << in.rdbuf();
    xml = text.str();
    directory = std::filesystem::path(spec.urdf_file).parent_path().string();
  }
  core::TriangleMesh surface = readVisualMesh(xml, body.urdf_link, sources.resolver, directory);
  for (Eigen::Vector3d& v : surface.vertices) v = body.pose * v;
  try {
    std::vector<std::string> found;
    core::SurfaceBody made = core::bodyFromSurface(std::move(surface), body.voxels, &found);
    if (warnings) {
      for (const std::string& w : found) warnings->push_back("link '" + body.urdf_link + "': " + w);
    }
    return made;
  } catch (const std::invalid_argument& e) {
    throw UrdfError("link '" + body.urdf_link + "': " + e.what());
  }
}

}  // namespace

std::vector<core::Mesh> readMeshes(const core::SceneSpec& spec, std::vector<std::string>* warnings,
                                   std::vector<std::optional<core::EmbeddedSurface>>* surfaces,
                                   const SurfaceSources& sources) {
  std::vector<core::Mesh> meshes;
  if (surfaces) surfaces->assign(spec.bodies.size(), std::nullopt);
  for (size_t b = 0; b < spec.bodies.size(); ++b) {
    const core::BodySpec& body = spec.bodies[b];
    if (body.box_mesh) {
      meshes.push_back(core::makeBoxMesh(body.box_mesh->min, body.box_mesh->max,
                                         body.box_mesh->cells, body.box_mesh->element));
      continue;
    }
    const std::string key = "bodies[" + std::to_string(b) + "].mesh";
    MeshReadResult read;
    try {
      if (body.surface_mesh) {
        core::SurfaceMeshSpec surface_mesh = *body.surface_mesh;
        if (sources.progress) {
          surface_mesh.voxels.progress = [&sources, &body](long done, long total) {
            sources.progress(body.name, done, total);
          };
        }
        core::SurfaceBody made = readSurfaceBodyOf(spec, surface_mesh, sources, warnings);
        meshes.push_back(std::move(made.voxels.mesh));
        if (surfaces) (*surfaces)[b] = std::move(made.surface);
        continue;
      }
      read = readMesh(body.mesh);
    } catch (const std::runtime_error& e) {  // MeshError, TriangleMeshError, UrdfError
      throw MeshError(whereInScene(spec.source, key) + key + ": " + e.what());
    }
    if (warnings) warnings->insert(warnings->end(), read.warnings.begin(), read.warnings.end());
    meshes.push_back(std::move(read.mesh));
  }
  return meshes;
}

core::Simulation buildSimulation(const core::SceneSpec& spec, std::vector<std::string>* warnings,
                                 const SurfaceSources& sources) {
  std::vector<std::optional<core::EmbeddedSurface>> surfaces;
  std::vector<core::Mesh> meshes = readMeshes(spec, warnings, &surfaces, sources);
  try {
    core::Simulation simulation(spec, std::move(meshes));
    for (size_t b = 0; b < surfaces.size(); ++b) {
      if (surfaces[b]) simulation.setEmbeddedSurface(static_cast<int>(b), std::move(*surfaces[b]));
    }
    simulation.refuseBodiesInsideEachOther();
    return simulation;
  } catch (const core::SpecError& e) {
    throw SceneError(locatedMessage(spec, e));
  } catch (const std::invalid_argument& e) {
    throw SceneError(e.what());
  }
}

}  // namespace deformable_sim::io
