// deformable_sim_mesh's command line: each bad argument is one line naming it and its value, then
// the usage, and exit status 2; cells too large for the part say so.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <string>

#include "command_output.h"

namespace {

using Result = deformable_sim::test::CommandOutput;

Result runMesh(const std::string& arguments) {
  return deformable_sim::test::runCommand(std::string(DEFORMABLE_SIM_MESH) + " " + arguments +
                                          " 2>&1");
}

const std::string kCube =
    std::string(DEFORMABLE_SIM_SOURCE_DIR) + "/test/data/meshes/cube_binary.stl";

// The arguments give exit status 2, a first line `error`, then the usage.
void expectUsageError(const std::string& arguments, const std::string& error) {
  const Result run = runMesh(arguments);
  EXPECT_EQ(run.exit_code, 2) << arguments << "\n" << run.output;
  const size_t end = run.output.find('\n');
  EXPECT_EQ(run.output.substr(0, end), "error: " + error) << arguments << "\n" << run.output;
  EXPECT_EQ(run.output.compare(end + 1, 6, "usage:"), 0) << arguments << "\n" << run.output;
}

}  // namespace

TEST(MeshTool, BadNumbersNameTheArgumentAndTheValue) {
  expectUsageError(kCube + " --cell-size 0", "--cell-size 0: must be > 0");
  expectUsageError(kCube + " --cell-size -0.5", "--cell-size -0.5: must be > 0");
  expectUsageError(kCube + " --cell-size nan", "--cell-size nan: must be > 0");
  expectUsageError(kCube + " --cell-size ten", "--cell-size ten: must be a number > 0");
  expectUsageError(kCube + " --cell-size inf", "--cell-size inf: must be finite");
  expectUsageError(kCube + " --cells 0", "--cells 0: must be >= 1");
  expectUsageError(kCube + " --cells -3", "--cells -3: must be >= 1");
  expectUsageError(kCube + " --cells 2.5", "--cells 2.5: must be a whole number >= 1");
  expectUsageError(kCube + " --cells 4 --max-cells 0", "--max-cells 0: must be >= 1");
  expectUsageError(kCube + " --cells 4 --max-cells 5000000000",
                   "--max-cells 5000000000: must be <= 2147483647");
}

TEST(MeshTool, UnknownMissingAndExtraArguments) {
  expectUsageError(kCube + " --cells 4 --fast", "unknown argument '--fast'");
  expectUsageError(kCube + " --cells", "--cells: missing its value");
  expectUsageError("--cells 4", "missing SURFACE");
  expectUsageError(kCube, "missing the grid's size: give --cell-size H or --cells N");
  expectUsageError(kCube + " other.stl --cells 4",
                   "one SURFACE only: '" + kCube + "' and 'other.stl'");
}

TEST(MeshTool, CellsTooLargeOrTooManySaySo) {
  const Result large = runMesh(kCube + " --cell-size 10");
  EXPECT_EQ(large.exit_code, 1) << large.output;
  EXPECT_NE(large.output.find("the cell size 10 m is too large for the part, 1 x 1 x 1 m"),
            std::string::npos)
      << large.output;
  const Result many = runMesh(kCube + " --cells 20 --max-cells 1000");
  EXPECT_EQ(many.exit_code, 1) << many.output;
  EXPECT_NE(many.output.find("20 x 20 x 20 = 8000 cells, more than max_cells (1000)"),
            std::string::npos)
      << many.output;
  EXPECT_NE(many.output.find("--max-cells M raises the limit"), std::string::npos) << many.output;
  const Result quick = runMesh(kCube + " --cells 4");
  EXPECT_EQ(quick.exit_code, 0) << quick.output;
}
