// Fuzz target: the scene file parser (YAML), and the simulation built from what it accepts.
//
// Input: the text of a scene file. parseScene may only throw SceneError, and what it accepts must
// be a scene that can run: bodies, a finite dt > 0, box meshes that can be generated. A scene whose
// bodies are all small generated boxes is built as the node builds it (readMeshes, Session; which
// may refuse it with std::invalid_argument, as documented: selections that select nothing, bad
// loads) and stepped; its state must stay finite. Mesh files named by the scene are not read: they
// are paths on this machine, not part of the input (the mesh readers have their own target).
// Corpus: test/fuzz/corpus/fuzz_scene_file.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/session/session.h"
#include "deformable_sim/io/scene_file.h"
#include "fuzz_checks.h"

namespace deformable_sim::fuzz {
namespace {

constexpr long kMaxSimulatedCells = 32;  // in all bodies: keeps runs fast

void simulate(const core::SceneSpec& spec) {
  long cells = 0;
  for (const core::BodySpec& body : spec.bodies) {
    if (!body.box_mesh) return;
    const Eigen::Vector3i& c = body.box_mesh->cells;
    require((c.array() >= 1).all(), "accepted a box mesh without cells");
    require(static_cast<long>(c.x()) * c.y() * c.z() <= core::kMaxBoxMeshCells,
            "accepted a box mesh of more than kMaxBoxMeshCells cells");
    if (c.maxCoeff() > kMaxSimulatedCells) return;
    cells += static_cast<long>(c.x()) * c.y() * c.z();
    if (cells > kMaxSimulatedCells) return;
  }
  std::vector<core::Mesh> meshes;
  try {
    meshes = io::readMeshes(spec, nullptr);
  } catch (const std::invalid_argument& e) {
    finding(std::string("the parser accepted a box mesh that cannot be made: ") + e.what());
  }
  std::unique_ptr<core::Session> session;
  try {
    session = std::make_unique<core::Session>(spec, std::move(meshes));
  } catch (const std::invalid_argument&) {
    return;  // refused, as documented
  }
  requireFinite(session->simulation(), "scene as built");
  stepAndCheck(session->simulation(), 3, "scene");
}

}  // namespace

void fuzzSceneFile(const uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  core::SceneSpec spec;
  try {
    spec = io::parseScene(text, "fuzz.yaml", "/nonexistent");
  } catch (const io::SceneError&) {
    return;  // refused, as documented
  }
  require(!spec.bodies.empty(), "accepted a scene without bodies");
  require(spec.dt > 0.0 && std::isfinite(spec.dt), "accepted a non-positive or infinite dt");
  simulate(spec);
}

}  // namespace deformable_sim::fuzz

DEFORMABLE_SIM_FUZZ_TARGET(deformable_sim::fuzz::fuzzSceneFile)
