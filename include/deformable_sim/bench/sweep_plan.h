// Which settings the bench runs: the full sweep behind the committed chart, or the short one CI
// runs and test_bench checks (meshes of levels 1 and 2 only, well under a minute).
#pragma once

#include <string>
#include <vector>

#include "deformable_sim/bench/bench_setting.h"

namespace deformable_sim::bench {

enum class SweepSize { kShort, kFull };

/// The settings in the order they run: cheap cases and coarse meshes first.
std::vector<BenchSetting> planSweep(SweepSize size);

/// The settings whose case is one of `cases` ("A", "B", "C2", "T").
std::vector<BenchSetting> selectCases(const std::vector<BenchSetting>& settings,
                                      const std::vector<std::string>& cases);

}  // namespace deformable_sim::bench
