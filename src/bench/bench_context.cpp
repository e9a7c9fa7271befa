#include "deformable_sim/bench/bench_context.h"

namespace deformable_sim::bench {

BenchContext::BenchContext(const std::string& reference_dir)
    : reference_dir_(reference_dir), results_(reference_dir + "/results.csv") {}

const ReferenceBeam& BenchContext::beam(const std::string& mesh) {
  std::unique_ptr<ReferenceBeam>& slot = beams_[mesh];
  if (slot) return *slot;
  double turn_degrees = 0.0;
  int cells = 0;
  if (ReferenceBeam::parseSurfaceId(mesh, &turn_degrees, &cells)) {
    slot = std::make_unique<ReferenceBeam>(ReferenceBeam::fromSurface(turn_degrees, cells));
  } else {
    slot = std::make_unique<ReferenceBeam>(reference_dir_, mesh);
  }
  return *slot;
}

}  // namespace deformable_sim::bench
