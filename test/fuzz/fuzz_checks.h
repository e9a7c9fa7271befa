// What the fuzz targets check beyond "no crash, no sanitizer report": what a reader accepts is
// valid, a simulation built from fuzzed input keeps a finite state, and a refused command leaves it
// as it was. A violated check throws Finding; under libFuzzer the entry point turns it into an
// abort (a crash with the input saved), in test_fuzz_corpus into a test failure.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "deformable_sim/core/session/simulation.h"

namespace deformable_sim::fuzz {

/// A violated check. Not derived from the exceptions the project throws, so that no handler of
/// a refusal can swallow it.
class Finding : public std::exception {
 public:
  explicit Finding(std::string what) : what_(std::move(what)) {}
  const char* what() const noexcept override { return what_.c_str(); }

 private:
  std::string what_;
};

[[noreturn]] inline void finding(const std::string& what) { throw Finding(what); }

inline void require(bool condition, const std::string& what) {
  if (!condition) finding(what);
}

/// Positions, velocities, applied and reaction forces of every body are finite.
inline void requireFinite(const core::Simulation& simulation, const std::string& when) {
  for (const core::Body& body : simulation.bodies()) {
    const std::string where = when + ", body '" + body.name() + "': ";
    require(body.positions().allFinite(), where + "non-finite position");
    require(body.velocities().allFinite(), where + "non-finite velocity");
    require(body.externalForces().allFinite(), where + "non-finite applied force");
    require(body.reactionForces().allFinite(), where + "non-finite reaction force");
  }
}

/// Steps `simulation` `steps` times, checking the state after each step.
inline void stepAndCheck(core::Simulation& simulation, int steps, const std::string& when) {
  std::vector<core::StepReport> reports;
  for (int s = 0; s < steps; ++s) {
    simulation.step(reports);
    requireFinite(simulation, when + ", after step " + std::to_string(s + 1));
  }
}

/// The fuzz targets' entry points: one input each. test_fuzz_corpus calls them directly.
void fuzzMeshReaders(const uint8_t* data, std::size_t size);
void fuzzSceneFile(const uint8_t* data, std::size_t size);
void fuzzCommands(const uint8_t* data, std::size_t size);
void fuzzSurfaces(const uint8_t* data, std::size_t size);

/// libFuzzer's callback: a finding is reported like a crash, with the input kept.
inline int runForLibFuzzer(void (*target)(const uint8_t*, std::size_t), const uint8_t* data,
                           std::size_t size) {
  try {
    target(data, size);
  } catch (const Finding& f) {
    std::fprintf(stderr, "\n== fuzz finding: %s\n", f.what());
    std::fflush(stderr);
    std::abort();
  }
  return 0;
}

}  // namespace deformable_sim::fuzz

// Defines LLVMFuzzerTestOneInput for `target`, except in test_fuzz_corpus, which links all
// targets into one program.
#ifdef DEFORMABLE_SIM_FUZZ_NO_MAIN
#define DEFORMABLE_SIM_FUZZ_TARGET(target)
#else
#define DEFORMABLE_SIM_FUZZ_TARGET(target)                                       \
  extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) { \
    return deformable_sim::fuzz::runForLibFuzzer(target, data, size);            \
  }
#endif
