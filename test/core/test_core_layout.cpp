// The core's folders and the one direction of their dependencies (doc/layout.md): every core file
// sits in a known folder, no folder grows past kMaxFiles headers or sources, and a file includes
// only core headers of its own folder or of folders below it in kOrder. A class per body model:
// each declares at most kMaxPublicMethods public methods, and only the bodies look at a model.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

/// The core's folders, lowest first: a folder may include its own and the earlier ones.
const std::vector<std::string> kOrder = {"base",      "solvers",        "geometry", "elements",
                                         "materials", "surface_bodies", "bodies",   "contact",
                                         "session",   "outputs",        "driver"};
constexpr int kMaxFiles = 15;
constexpr int kMaxPublicMethods = 25;

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

std::string contents(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Names of the public member functions that `class name` declares in `source` (overloads once;
/// constructors, destructor and operators left out). Reads declarations at the class's own brace
/// depth, so inline bodies and nested types do not count.
std::vector<std::string> publicMethods(const std::string& source, const std::string& name) {
  static const std::regex method(R"(^\s*(?:[\w:<>,*&~]+\s+)*?~?(\w+)\s*\()");
  const size_t start = source.find("class " + name + " ");
  if (start == std::string::npos) return {};
  std::istringstream lines(source.substr(start));
  std::vector<std::string> names;
  std::string line;
  int depth = 0;
  bool in_public = false;
  while (std::getline(lines, line)) {
    const std::string trimmed = line.substr(std::min(line.find_first_not_of(' '), line.size()));
    if (depth == 1 && trimmed.rfind("public:", 0) == 0) in_public = true;
    if (depth == 1 && (trimmed.rfind("protected:", 0) == 0 || trimmed.rfind("private:", 0) == 0))
      in_public = false;
    std::smatch match;
    if (depth == 1 && in_public && trimmed.rfind("//", 0) != 0 &&
        std::regex_search(line, match, method)) {
      const std::string found = match[1];
      if (found != name && found.rfind("operator", 0) != 0 &&
          std::find(names.begin(), names.end(), found) == names.end()) {
        names.push_back(found);
      }
    }
    for (char c : line) depth += (c == '{') - (c == '}');
    if (depth == 0 && line.find('}') != std::string::npos) break;
  }
  return names;
}

/// Whether a line of code chooses by a body's model: compares with or switches on a BodyModel.
bool choosesByModel(const std::string& line) {
  static const std::regex choice(
      R"((case\s+BodyModel::)|([!=]=\s*(core::)?BodyModel::)|(BodyModel::\w+\s*[!=]=))");
  return std::regex_search(line, choice);
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

TEST(CoreLayout, TheMethodCountReadsOnlyTheClassesOwnPublicDeclarations) {
  const std::string source = R"(
class Other {
 public:
  void elsewhere();
};
class Shape : public Base {
 public:
  Shape(int sides);
  virtual ~Shape();
  Shape& operator=(const Shape&) = delete;
  /// area() in a comment
  double area() const { return helper(1) * 2.0; }
  const std::vector<int>& sides() const;
  void move(double x);
  void move(double x, double y);
  struct Corner {
    void inside();
  };
 protected:
  void hidden();
};
)";
  EXPECT_EQ(publicMethods(source, "Shape"), (std::vector<std::string>{"area", "sides", "move"}));
  EXPECT_TRUE(choosesByModel("  if (model == BodyModel::kRigid) {"));
  EXPECT_TRUE(choosesByModel("    case BodyModel::kPseudoRigid:"));
  EXPECT_TRUE(choosesByModel("  return BodyModel::kRigid != m;"));
  EXPECT_FALSE(choosesByModel("  BodyModel model = BodyModel::kFiniteElement;"));
  EXPECT_FALSE(choosesByModel("  s.model = core::modelName(body.settings().model);"));
}

TEST(CoreLayout, ABodyClassDeclaresAtMostTwentyFivePublicMethods) {
  const fs::path bodies =
      fs::path(DEFORMABLE_SIM_SOURCE_DIR) / "include/deformable_sim/core/bodies";
  const std::map<std::string, std::string> classes = {
      {"body.h", "Body"},
      {"finite_element_body.h", "FiniteElementBody"},
      {"reduced_body.h", "ReducedBody"}};
  for (const auto& [header, name] : classes) {
    const std::vector<std::string> methods = publicMethods(contents(bodies / header), name);
    EXPECT_GT(methods.size(), 5u) << name << ": the count found no methods";
    EXPECT_LE(methods.size(), static_cast<size_t>(kMaxPublicMethods))
        << name << " declares " << methods.size() << " public methods";
  }
}

TEST(CoreLayout, OnlyTheBodiesChooseByABodysModel) {
  for (const CoreFile& file : coreFiles()) {
    if (file.folder == "bodies") continue;
    std::ifstream in(file.path);
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
      EXPECT_FALSE(choosesByModel(line))
          << file.path.string() << ":" << number << ": " << line
          << " (a model's behaviour belongs to its body class, made by makeBody())";
    }
  }
}
