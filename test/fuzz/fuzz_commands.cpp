// Fuzz target: the command layer behind the node's message handlers (~wrench, ~node_wrench,
// ~fixed_nodes, ~grasp, obstacle poses from tf, live tuning, ~reset), driven as a hostile
// publisher would drive it.
//
// The node turns each message into a core::SessionCommand (frames resolved to world poses) and
// hands it to core::Session::apply, which checks it and applies it between steps; the checks live
// there, ROS-free. Here the input bytes are decoded into a sequence of such commands, with
// whatever values a message can carry (NaN, infinities, huge and negative numbers, unknown
// names, several node targets at once, frames that are not rotations) and timer ticks in
// between, applied to a small live simulation: a clamped beam with node groups and a free block,
// with contact against a floor.
//
// Checked: Session::apply throws nothing but CommandError; a refused command leaves the
// simulation as it was; the state stays finite after every command and every step.
// Corpus: test/fuzz/corpus/fuzz_commands (see FuzzedInput for the encoding).
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "deformable_sim/core/session/session.h"
#include "deformable_sim/io/scene_file.h"
#include "fuzz_checks.h"

namespace deformable_sim::fuzz {
namespace {

// The input, read front to back; past its end every read gives zero (an empty name, no nodes),
// so every prefix of an input is an input.
class FuzzedInput {
 public:
  FuzzedInput(const uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  bool done() const { return at_ >= size_; }
  uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
  bool flag() { return byte() & 1; }

  // Numbers a message may carry: a byte picks a special value, a small multiple of 1/64, or the
  // next eight bytes as they are.
  double number() {
    static const double kSpecial[] = {0.0,
                                      1.0,
                                      -1.0,
                                      0.05,
                                      1.0e-3,
                                      1.0e4,
                                      1.0e5,
                                      1.0e300,
                                      -1.0e300,
                                      std::numeric_limits<double>::quiet_NaN(),
                                      std::numeric_limits<double>::infinity(),
                                      -std::numeric_limits<double>::infinity(),
                                      std::numeric_limits<double>::denorm_min(),
                                      std::numeric_limits<double>::max(),
                                      -0.0,
                                      0.49999};
    constexpr int kNumSpecial = sizeof kSpecial / sizeof kSpecial[0];
    const uint8_t choice = byte();
    if (choice < kNumSpecial) return kSpecial[choice];
    if (choice < 250) return static_cast<int8_t>(byte()) / 64.0;
    uint64_t bits = 0;
    for (int k = 0; k < 8; ++k) bits = bits << 8 | byte();
    double value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }

  Eigen::Vector3d vector3() {
    const double x = number(), y = number(), z = number();
    return {x, y, z};
  }

  // One of `names` (the scene's bodies, groups, ...), or a short string of the input's bytes.
  std::string name(const std::vector<std::string>& names) {
    const uint8_t choice = byte();
    if (choice < 240) return names[choice % names.size()];
    std::string text;
    for (int n = byte() % 8; n > 0; --n) text += static_cast<char>(byte());
    return text;
  }

  long nodeNumber() {
    static const long kSpecial[] = {0, -1, std::numeric_limits<long>::max(),
                                    std::numeric_limits<long>::min(), 1L << 32};
    const uint8_t choice = byte();
    if (choice < 5) return kSpecial[choice];
    return choice % 24;  // the beam has 12 nodes, the block 8 (numbered from 1)
  }

  // The identity, a rotation (quaternion, normalised as tf2 does) and translation, or any matrix.
  Eigen::Isometry3d pose() {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    switch (byte() % 3) {
      case 0:
        break;
      case 1: {
        Eigen::Quaterniond q(number(), number(), number(), number());
        if (q.norm() > 0.0) q.normalize();
        pose.linear() = q.toRotationMatrix();
        pose.translation() = vector3();
        break;
      }
      default:
        for (int r = 0; r < 3; ++r) {
          for (int c = 0; c < 4; ++c) pose.matrix()(r, c) = number();
        }
    }
    return pose;
  }

  core::Shape shape() {
    core::Shape shape;
    shape.kind = static_cast<core::Shape::Kind>(byte() % 3);
    shape.size = vector3();
    shape.radius = number();
    shape.length = number();
    return shape;
  }

  std::vector<core::PlacedShape> shapes() {
    std::vector<core::PlacedShape> shapes(byte() % 3);
    for (core::PlacedShape& placed : shapes) {
      placed.name = name({"pad", "floor", ""});
      placed.shape = shape();
      placed.pose = pose();
    }
    return shapes;
  }

  // A byte of flags says which of the (exclusive) target kinds are given: several at once or none
  // must be refused.
  core::NodeTarget nodes() {
    core::NodeTarget target;
    const uint8_t kinds = byte();
    if (kinds & 1) {
      for (int n = byte() % 6; n > 0; --n) target.node_numbers.push_back(nodeNumber());
    }
    if (kinds & 2) target.group = name({"tip", "corner", "", "none"});
    if (kinds & 4) target.box = core::Box{vector3(), vector3()};
    if (kinds & 8) target.sphere = core::Sphere{vector3(), number()};
    if (kinds & 16) {
      target.shapes = shapes();
      target.shape_margin = number();
    }
    target.whole_body = kinds & 32;
    if (kinds & 64) target.region_pose = pose();
    return target;
  }

 private:
  const uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
};

const std::vector<std::string> kBodies = {"beam", "block", "", "nobody"};
const std::vector<std::string> kSources = {"beam/tip", "tool", "node_wrench/beam/tip", ""};
const std::vector<std::string> kGrasps = {"left", "right", ""};

core::SessionCommand decodeCommand(FuzzedInput& in, uint8_t kind) {
  switch (kind) {
    case 0: {
      core::WrenchCommand c;
      c.source = in.name(kSources);
      c.body = in.name(kBodies);
      c.nodes = in.nodes();
      c.force = in.vector3();
      c.torque = in.vector3();
      if (in.flag()) c.point = in.vector3();
      return c;
    }
    case 1:
      return core::ClearWrenchCommand{in.name(kSources)};
    case 2: {
      core::FixCommand c;
      c.body = in.name(kBodies);
      c.nodes = in.nodes();
      c.fix = !in.flag();
      for (int n = in.byte() % 5; n > 0; --n) c.targets.push_back(in.vector3());
      if (in.flag()) c.translation = in.vector3();
      return c;
    }
    case 3: {
      core::GraspCommand c;
      c.name = in.name(kGrasps);
      c.body = in.name(kBodies);
      c.nodes = in.nodes();
      c.frame = in.pose();
      return c;
    }
    case 4:
      return core::ReleaseGraspCommand{in.name(kGrasps)};
    case 5: {
      core::MoveGraspCommand c;
      c.name = in.name(kGrasps);
      c.frame = in.pose();
      return c;
    }
    case 6:
      return core::SetObstaclesCommand{in.shapes()};
    case 7: {
      core::TuneCommand c;
      c.body = in.name(kBodies);
      const uint8_t given = in.byte();
      if (given & 1)
        c.material = core::LinearElasticMaterial{in.number(), in.number(), in.number()};
      if (given & 2) c.damping = core::RayleighDamping{in.number(), in.number()};
      if (given & 4) c.solver_tolerance = in.number();
      // Iterations from a short list: a user may ask for a billion, which is slow, not wrong.
      static const int kIterations[] = {0, -1, 1, 3, 200, std::numeric_limits<int>::min()};
      if (given & 8) c.solver_max_iterations = kIterations[in.byte() % 6];
      if (given & 16) c.dt = in.number();
      return c;
    }
    default:
      return core::ResetCommand{};
  }
}

// The scene: small enough that a step takes microseconds.
const char kScene[] = R"(
dt: 0.01
effects:
  gravity: [0, 0, -9.81]
  warping: true
  damping: {mass: 1.0, stiffness: 0.002}
  contact: {friction: 0.5}
obstacles: [{name: floor, box: {size: [2, 2, 0.1]}, position: [0, 0, -0.1]}]
solver: {max_iterations: 200}
bodies:
  - name: beam
    mesh: {box: {min: [0, -0.025, 0], max: [0.2, 0.025, 0.05], cells: [2, 1, 1]}}
    material: {youngs_modulus: 1.0e5, poisson_ratio: 0.3, density: 100.0}
    fixed: [{box: {min: [-1.0e-6, -1, -1], max: [1.0e-6, 1, 1]}}]
    groups:
      tip: {box: {min: [0.199999, -1, -1], max: [0.200001, 1, 1]}}
      corner: {nodes: [3]}
    wrench_radius: 0.05
  - name: block
    mesh: {box: {min: [0.3, 0, 0], max: [0.35, 0.05, 0.05], cells: [1, 1, 1]}}
    material: {youngs_modulus: 3.0e4, poisson_ratio: 0.3, density: 150.0}
)";

// What a command can change, to compare before and after a refused one.
struct Snapshot {
  std::vector<Eigen::VectorXd> positions, velocities, forces;
  std::vector<std::vector<bool>> constrained;
  std::vector<std::vector<double>> settings;  // material, solver limits
  std::vector<std::string> wrenches, grasps;
  std::size_t obstacles = 0;
  double dt = 0.0;
  long episode = 0;

  explicit Snapshot(const core::Session& session)
      : obstacles(session.simulation().obstacles().size()),
        dt(session.simulation().dt()),
        episode(session.episode()) {
    for (const core::Body& body : session.simulation().bodies()) {
      positions.push_back(body.positions());
      velocities.push_back(body.velocities());
      forces.push_back(body.externalForces());
      constrained.emplace_back();
      for (int i = 0; i < body.numNodes(); ++i) constrained.back().push_back(body.isConstrained(i));
      settings.push_back({body.settings().material.youngs_modulus,
                          body.settings().material.poisson_ratio, body.settings().material.density,
                          body.settings().solver.tolerance,
                          static_cast<double>(body.settings().solver.max_iterations)});
    }
    for (const auto& [source, wrench] : session.commands().activeWrenches()) {
      wrenches.push_back(source);
    }
    for (const auto& [name, grasp] : session.commands().grasps()) grasps.push_back(name);
  }

  bool operator==(const Snapshot& o) const {
    return positions == o.positions && velocities == o.velocities && forces == o.forces &&
           constrained == o.constrained && settings == o.settings && wrenches == o.wrenches &&
           grasps == o.grasps && obstacles == o.obstacles && dt == o.dt && episode == o.episode;
  }
};

}  // namespace

void fuzzCommands(const uint8_t* data, std::size_t size) {
  constexpr int kMaxRecords = 64;
  constexpr int kNumCommandKinds = 9;
  static const core::SceneSpec spec = io::parseScene(kScene, "fuzz scene", ".");
  static const std::vector<core::Mesh> meshes = io::readMeshes(spec, nullptr);
  core::Session session(spec, meshes);
  std::vector<core::StepReport> reports;
  // DEFORMABLE_SIM_FUZZ_VERBOSE=1: what became of each command (when writing corpus inputs).
  static const bool verbose = std::getenv("DEFORMABLE_SIM_FUZZ_VERBOSE") != nullptr;

  FuzzedInput in(data, size);
  for (int record = 0; record < kMaxRecords && !in.done(); ++record) {
    // A record: a kind byte, then the command's fields; kinds past the commands are ticks.
    const uint8_t kind = in.byte() % 12;
    if (kind >= kNumCommandKinds) {
      for (int s = kind - kNumCommandKinds; s >= 0; --s) {
        session.step(reports);
        requireFinite(session.simulation(), "after a step");
      }
      continue;
    }
    const core::SessionCommand command = decodeCommand(in, kind);
    const Snapshot before(session);
    try {
      const int nodes = session.apply(command);
      if (verbose) std::fprintf(stderr, "command kind %d: applied to %d nodes\n", kind, nodes);
    } catch (const core::CommandError& e) {
      if (verbose) std::fprintf(stderr, "command kind %d: refused: %s\n", kind, e.what());
      require(Snapshot(session) == before,
              "a refused command (kind " + std::to_string(kind) + ") changed the simulation");
      continue;
    }
    requireFinite(session.simulation(), "after command kind " + std::to_string(kind));
  }
  session.step(reports);
  requireFinite(session.simulation(), "after the last step");
}

}  // namespace deformable_sim::fuzz

DEFORMABLE_SIM_FUZZ_TARGET(deformable_sim::fuzz::fuzzCommands)
