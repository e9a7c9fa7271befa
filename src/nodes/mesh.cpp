// deformable_sim_mesh: makes the grid of a body from a surface (STL, DAE, OBJ), prints what it
// holds and writes it as a Gmsh file. No ROS.
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "deformable_sim/core/base/late_progress_bar.h"
#include "deformable_sim/core/surface_bodies/voxelization.h"
#include "deformable_sim/io/gmsh_writer.h"
#include "deformable_sim/io/surface_body_reader.h"

namespace {

constexpr const char* kUsage =
    "usage: deformable_sim_mesh SURFACE (--cell-size H | --cells N) [--max-cells M] "
    "[--out OUT.msh]\n"
    "  SURFACE        a closed surface: STL, DAE, OBJ (as the scene key mesh: {surface: ..})\n"
    "  --cell-size H  the grid's cell size, m\n"
    "  --cells N      or N cells along the longest side of the surface's bounding box\n"
    "  --max-cells M  refuse a grid of more than M cells (default 1000000, at most\n"
    "                 2147483647; the scene key max_cells)\n"
    "  --out OUT.msh  write the grid's hexahedra as a Gmsh 2.2 ASCII file\n"
    "  --help, -h     print this usage and exit\n"
    "Prints the cells, nodes, the part of the mass in cells the surface cuts, the volume the\n"
    "surface encloses against the grid's, and the time it took; a bar on stderr shows the\n"
    "progress of a grid that takes more than a second.\n";

constexpr long kMostCellsAlongASide = 100000;

struct Options {
  std::string surface, out;
  deformable_sim::core::VoxelSettings settings;
};

enum class Parsed { kRun, kHelp, kBad };

// The argument's value as a number, or an error naming the argument and the value.
double positiveValue(const std::string& arg, const std::string& value, std::string& error) {
  char* end = nullptr;
  const double number = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0') {
    error = arg + " " + value + ": must be a number > 0";
  } else if (!(number > 0.0)) {
    error = arg + " " + value + ": must be > 0";
  } else if (!std::isfinite(number)) {
    error = arg + " " + value + ": must be finite";
  }
  return number;
}

// The argument's value as a whole number in [1, most], or an error naming them.
long countValue(const std::string& arg, const std::string& value, long most, std::string& error) {
  char* end = nullptr;
  errno = 0;
  const long count = std::strtol(value.c_str(), &end, 10);
  if (value.empty() || *end != '\0' || errno == ERANGE) {
    error = arg + " " + value + ": must be a whole number >= 1";
  } else if (count < 1) {
    error = arg + " " + value + ": must be >= 1";
  } else if (count > most) {
    error = arg + " " + value + ": must be <= " + std::to_string(most);
  }
  return count;
}

// Fills `options` from one option with a value; false for an option this tool does not take.
bool takeOption(const std::string& arg, const std::string& value, Options& options,
                std::string& error) {
  if (arg == "--cell-size") {
    options.settings.cell_size = positiveValue(arg, value, error);
  } else if (arg == "--cells") {
    options.settings.longest_side_cells =
        static_cast<int>(countValue(arg, value, kMostCellsAlongASide, error));
  } else if (arg == "--max-cells") {
    options.settings.max_cells =
        countValue(arg, value, deformable_sim::core::kMostGridCells, error);
  } else if (arg == "--out") {
    options.out = value;
  } else {
    return false;
  }
  return true;
}

// The options of the command line; `error` names what is wrong when it returns kBad.
Parsed parseArguments(int argc, char** argv, Options& options, std::string& error) {
  for (int i = 1; i < argc && error.empty(); ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") return Parsed::kHelp;
    if (arg.size() > 1 && arg[0] == '-') {
      const bool known =
          arg == "--cell-size" || arg == "--cells" || arg == "--max-cells" || arg == "--out";
      if (!known) {
        error = "unknown argument '" + arg + "'";
      } else if (i + 1 >= argc) {
        error = arg + ": missing its value";
      } else {
        takeOption(arg, argv[++i], options, error);
      }
    } else if (options.surface.empty()) {
      options.surface = arg;
    } else {
      error = "one SURFACE only: '" + options.surface + "' and '" + arg + "'";
    }
  }
  if (error.empty() && options.surface.empty()) error = "missing SURFACE";
  const bool sized = options.settings.cell_size > 0.0 || options.settings.longest_side_cells > 0;
  if (error.empty() && !sized) error = "missing the grid's size: give --cell-size H or --cells N";
  return error.empty() ? Parsed::kRun : Parsed::kBad;
}

int run(Options options) {
  namespace core = deformable_sim::core;
  const auto start = std::chrono::steady_clock::now();
  core::LateProgressBar bar(stderr, "grid cells voxelized");
  options.settings.progress = [&bar](long done, long total) { bar.update(done, total); };
  std::vector<std::string> warnings;
  std::optional<core::SurfaceBody> read;
  try {
    read.emplace(deformable_sim::io::readSurfaceBody(options.surface, options.settings, &warnings));
  } catch (...) {
    bar.finish();  // so that the error starts a line of its own
    throw;
  }
  bar.finish();
  const core::SurfaceBody& body = *read;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
  const core::Voxelization& voxels = body.voxels;
  const double grid_volume = core::totalVolume(voxels.mesh);
  std::printf("surface %s: %d vertices, %zu triangles\n", options.surface.c_str(),
              body.surface.numVertices(), body.surface.triangles().size());
  std::printf("grid: cell size %.6g m, %d x %d x %d\n", voxels.grid.cell_size,
              voxels.grid.cells.x(), voxels.grid.cells.y(), voxels.grid.cells.z());
  std::printf("cells: %zu\nnodes: %d\n", voxels.mesh.cells.size(), voxels.mesh.numNodes());
  std::printf("mass in partial cells: %.4f\n", core::partialCellMassFraction(voxels.mesh));
  std::printf("enclosed volume: %.9g m^3\n", voxels.enclosed_volume);
  std::printf("grid volume: %.9g m^3 (%+.4f %% of the enclosed)\n", grid_volume,
              100.0 * (grid_volume / voxels.enclosed_volume - 1.0));
  std::printf("pieces: %zu\ntime: %.3f s\n", voxels.piece_sizes.size(), seconds);
  if (!options.out.empty()) deformable_sim::io::writeGmshFile(voxels.mesh, options.out);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  std::string error;
  switch (parseArguments(argc, argv, options, error)) {
    case Parsed::kHelp:
      std::cout << kUsage;
      return 0;
    case Parsed::kBad:
      std::cerr << "error: " << error << "\n" << kUsage;
      return 2;
    case Parsed::kRun:
      break;
  }
  try {
    return run(options);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    if (std::string(e.what()).find("raise max_cells") != std::string::npos) {
      std::cerr << "(here --max-cells M raises the limit)\n";
    }
    return 1;
  }
}
