// deformable_sim_mesh: makes the grid of a body from a surface (STL, DAE, OBJ), prints what it
// holds and writes it as a Gmsh file. No ROS.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "deformable_sim/io/gmsh_writer.h"
#include "deformable_sim/io/surface_body_reader.h"

namespace {

constexpr const char* kUsage =
    "usage: deformable_sim_mesh SURFACE (--cell-size H | --cells N) [--out OUT.msh]\n"
    "  SURFACE        a closed surface: STL, DAE, OBJ (as the scene key mesh: {surface: ..})\n"
    "  --cell-size H  the grid's cell size, m\n"
    "  --cells N      or N cells along the longest side of the surface's bounding box\n"
    "  --out OUT.msh  write the grid's hexahedra as a Gmsh 2.2 ASCII file\n"
    "  --help, -h     print this usage and exit\n"
    "Prints the cells, nodes, the part of the mass in cells the surface cuts, the volume the\n"
    "surface encloses against the grid's, and the time it took.\n";

struct Options {
  std::string surface, out;
  deformable_sim::core::VoxelSettings settings;
};

enum class Parsed { kRun, kHelp, kBad };

Parsed parseArguments(int argc, char** argv, Options& options) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    char* end = nullptr;
    if (arg == "--help" || arg == "-h") return Parsed::kHelp;
    if (arg == "--cell-size" && i + 1 < argc) {
      options.settings.cell_size = std::strtod(argv[++i], &end);
      if (*end != '\0' || !(options.settings.cell_size > 0.0)) return Parsed::kBad;
    } else if (arg == "--cells" && i + 1 < argc) {
      const long cells = std::strtol(argv[++i], &end, 10);
      if (*end != '\0' || cells < 1 || cells > 100000) return Parsed::kBad;
      options.settings.longest_side_cells = static_cast<int>(cells);
    } else if (arg == "--out" && i + 1 < argc) {
      options.out = argv[++i];
    } else if (!arg.empty() && arg[0] != '-' && options.surface.empty()) {
      options.surface = arg;
    } else {
      return Parsed::kBad;
    }
  }
  const bool sized = options.settings.cell_size > 0.0 || options.settings.longest_side_cells > 0;
  return options.surface.empty() || !sized ? Parsed::kBad : Parsed::kRun;
}

int run(const Options& options) {
  namespace core = deformable_sim::core;
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::string> warnings;
  const core::SurfaceBody body =
      deformable_sim::io::readSurfaceBody(options.surface, options.settings, &warnings);
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
  switch (parseArguments(argc, argv, options)) {
    case Parsed::kHelp:
      std::cout << kUsage;
      return 0;
    case Parsed::kBad:
      std::cerr << kUsage;
      return 2;
    case Parsed::kRun:
      break;
  }
  try {
    return run(options);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
