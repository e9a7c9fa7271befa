#include "deformable_sim/bench/bench_context.h"

namespace deformable_sim::bench {

BenchContext::BenchContext(const std::string& reference_dir)
    : reference_dir_(reference_dir), results_(reference_dir + "/results.csv") {}

const ReferenceBeam& BenchContext::beam(const std::string& mesh) {
  std::unique_ptr<ReferenceBeam>& slot = beams_[mesh];
  if (!slot) slot = std::make_unique<ReferenceBeam>(reference_dir_, mesh);
  return *slot;
}

}  // namespace deformable_sim::bench
