// The fuzz targets' entry points, built with the ordinary compiler and without libFuzzer, on every
// input of the committed corpus (test/fuzz/corpus/<target>/) and every crash the fuzzers found
// (test/fuzz/crashes/<target>/): a fixed crash stays fixed in the ordinary test run.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_checks.h"

namespace {

namespace fs = std::filesystem;
using deformable_sim::fuzz::Finding;

const fs::path kFuzzDir = fs::path(DEFORMABLE_SIM_SOURCE_DIR) / "test" / "fuzz";

std::vector<fs::path> inputsOf(const std::string& target) {
  std::vector<fs::path> inputs;
  for (const char* kind : {"corpus", "crashes"}) {
    const fs::path dir = kFuzzDir / kind / target;
    if (!fs::is_directory(dir)) continue;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
      if (entry.is_regular_file()) inputs.push_back(entry.path());
    }
  }
  return inputs;
}

// Runs `target` on each input; a finding or an escaped exception fails the test naming the file.
void runAll(const std::string& target, void (*entry)(const uint8_t*, std::size_t)) {
  const std::vector<fs::path> inputs = inputsOf(target);
  ASSERT_FALSE(inputs.empty()) << "no corpus for " << target;
  for (const fs::path& path : inputs) {
    std::ifstream file(path, std::ios::binary);
    const std::vector<char> bytes{std::istreambuf_iterator<char>(file),
                                  std::istreambuf_iterator<char>()};
    try {
      entry(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
    } catch (const Finding& f) {
      ADD_FAILURE() << path << ": " << f.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << path << ": unexpected exception: " << e.what();
    }
  }
}

TEST(FuzzCorpus, MeshReaders) {
  runAll("fuzz_mesh_readers", deformable_sim::fuzz::fuzzMeshReaders);
}

TEST(FuzzCorpus, SceneFile) { runAll("fuzz_scene_file", deformable_sim::fuzz::fuzzSceneFile); }

TEST(FuzzCorpus, Commands) { runAll("fuzz_commands", deformable_sim::fuzz::fuzzCommands); }

TEST(FuzzCorpus, Surfaces) { runAll("fuzz_surfaces", deformable_sim::fuzz::fuzzSurfaces); }

}  // namespace
