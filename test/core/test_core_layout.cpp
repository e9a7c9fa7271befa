// The core's folders and the one direction of their dependencies (doc/layout.md): every core file
// sits in a known folder, no folder grows past kMaxFiles headers or sources, and a file includes
// only core headers of its own folder or of folders below it in kOrder.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

/// The core's folders, lowest first: a folder may include its own and the earlier ones.
const std::vector<std::string> kOrder = {"base",           "solvers", "geometry", "elements",
                                         "surface_bodies", "bodies",  "contact",  "session",
                                         "outputs",        "driver"};
constexpr int kMaxFiles = 15;

/// kOrder's index of a folder, or -1 if it is not a folder of the core.
int rankOf(const std::string& folder) {
  const auto it = std::find(kOrder.begin(), kOrder.end(), folder);
  return it == kOrder.end() ? -1 : static_cast<int>(it - kOrder.begin());
}

/// What is wrong with an include line of a file in `folder`, or "" when nothing is: a header
/// of a later folder, of no or an unknown folder, or not of the core at all (io, ros, bench,
/// perf are layers above it; a relative path hides where it points).
std::string wrongWay(const std::string& folder, const std::string& line) {
  static const std::regex quoted(R"(^\s*#\s*include\s*"([^"]*)\")");
  static const std::regex core(R"(^deformable_sim/core/(?:([a-z_]+)/)?[a-z_]+\.h$)");
  std::smatch include;
  if (!std::regex_search(line, include, quoted)) return "";  // <system> headers
  const std::string header = include[1];
  std::smatch match;
  if (!std::regex_match(header, match, core)) return header + " is not a core header";
  const std::string target = match[1];
  if (target.empty()) return header + " names no folder of the core";
  if (rankOf(target) < 0) return header + " is in no known folder of the core";
  if (rankOf(target) > rankOf(folder)) {
    return header + " is in " + target + ", above " + folder + " in the order of folders";
  }
  return "";
}

struct CoreFile {
  fs::path path;
  std::string folder;  ///< its folder under core/ ("" directly in core/)
  bool header;
};

std::vector<CoreFile> coreFiles() {
  std::vector<CoreFile> files;
  for (const char* root : {"include/deformable_sim/core", "src/core"}) {
    const fs::path dir = fs::path(DEFORMABLE_SIM_SOURCE_DIR) / root;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
      if (!entry.is_regular_file()) continue;
      const fs::path relative = entry.path().lexically_relative(dir);
      const std::string folder =
          std::distance(relative.begin(), relative.end()) > 1 ? relative.begin()->string() : "";
      files.push_back({entry.path(), folder, entry.path().extension() == ".h"});
    }
  }
  return files;
}

}  // namespace

TEST(CoreLayout, TheCheckTellsEachWrongWayApart) {
  EXPECT_EQ(wrongWay("bodies", R"(#include "deformable_sim/core/elements/mesh.h")"), "");
  EXPECT_EQ(wrongWay("bodies", R"(#include "deformable_sim/core/bodies/body.h")"), "");
  EXPECT_EQ(wrongWay("bodies", "#include <Eigen/Core>"), "");
  EXPECT_EQ(wrongWay("solvers", R"(#include "deformable_sim/core/elements/mesh.h")"),
            "deformable_sim/core/elements/mesh.h is in elements, above solvers in the order of "
            "folders");
  EXPECT_EQ(wrongWay("session", R"(#include "deformable_sim/core/mesh.h")"),
            "deformable_sim/core/mesh.h names no folder of the core");
  EXPECT_EQ(wrongWay("session", R"(#include "deformable_sim/core/misc/mesh.h")"),
            "deformable_sim/core/misc/mesh.h is in no known folder of the core");
  EXPECT_EQ(wrongWay("driver", R"(#include "deformable_sim/io/scene_file.h")"),
            "deformable_sim/io/scene_file.h is not a core header");
  EXPECT_EQ(wrongWay("driver", R"(#include "../base/spin_barrier.h")"),
            "../base/spin_barrier.h is not a core header");
}

TEST(CoreLayout, EveryFileSitsInAKnownFolder) {
  const std::vector<CoreFile> files = coreFiles();
  EXPECT_GT(files.size(), 100u);
  for (const CoreFile& file : files) {
    EXPECT_GE(rankOf(file.folder), 0) << file.path.string() << " is in no folder of the core ("
                                      << "doc/layout.md says where a new file goes)";
  }
}

TEST(CoreLayout, NoFolderHoldsMoreThanFifteenHeadersOrSources) {
  std::map<std::string, int> headers, sources;
  for (const CoreFile& file : coreFiles()) ++(file.header ? headers : sources)[file.folder];
  for (const auto& [folder, count] : headers) {
    EXPECT_LE(count, kMaxFiles) << "include/deformable_sim/core/" << folder << ": " << count
                                << " headers; split it by subsystem";
  }
  for (const auto& [folder, count] : sources) {
    EXPECT_LE(count, kMaxFiles) << "src/core/" << folder << ": " << count
                                << " sources; split it by subsystem";
  }
}

TEST(CoreLayout, IncludesPointDownTheOrderOfFolders) {
  int includes = 0;
  for (const CoreFile& file : coreFiles()) {
    std::ifstream in(file.path);
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
      if (line.find("deformable_sim/") != std::string::npos) ++includes;
      const std::string wrong = wrongWay(file.folder, line);
      EXPECT_EQ(wrong, "") << file.path.string() << ":" << number << " (" << file.folder
                           << "): " << line;
    }
  }
  EXPECT_GT(includes, 200);
}
