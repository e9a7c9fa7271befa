// deformable_sim_bench: what accuracy costs in time. Sweeps mesh, warping, step, substeps and
// solver settings over the reference cases of ../shared/reference and writes one CSV row per
// setting and comparison (columns: include/deformable_sim/bench/result_csv.h).
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "deformable_sim/bench/bench_context.h"
#include "deformable_sim/bench/result_csv.h"
#include "deformable_sim/bench/sweep_plan.h"
#include "deformable_sim/bench/sweep_runner.h"
#include "deformable_sim/core/base/progress_bar.h"

namespace {

namespace bench = deformable_sim::bench;

constexpr const char* kUsage =
    "usage: deformable_sim_bench [--short] [--out FILE.csv] [--reference DIR] [--repeat N]\n"
    "                            [--cases A,B,C2,T]\n"
    "  --short          levels 1-2 and a few settings per knob (CI; well under a minute)\n"
    "  --out FILE       write the CSV there (default: standard output)\n"
    "  --reference DIR  the reference cases (default: ../shared/reference beside the source)\n"
    "  --repeat N       run every setting up to N times for its timing (default 3; a setting\n"
    "                   stops repeating once its runs have taken 3 s)\n"
    "  --cases LIST     only these cases: A (static), B (large deflection), C2 (free vibration),\n"
    "                   T (dynamic trajectory)\n"
    "  --help, -h       print this usage and exit\n"
    "A progress bar goes to standard error.\n";

struct Options {
  bench::SweepSize size = bench::SweepSize::kFull;
  std::string out;
  std::string reference = DEFORMABLE_SIM_REFERENCE_DIR;
  int repeat = 3;
  std::vector<std::string> cases = {"A", "B", "C2", "T"};
};

enum class Parsed { kRun, kHelp, kBad };

Parsed parseArguments(int argc, char** argv, Options& options) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--help" || arg == "-h") return Parsed::kHelp;
    if (arg == "--short") {
      options.size = bench::SweepSize::kShort;
    } else if (arg == "--out" && has_value) {
      options.out = argv[++i];
    } else if (arg == "--reference" && has_value) {
      options.reference = argv[++i];
    } else if (arg == "--repeat" && has_value) {
      char* end = nullptr;
      options.repeat = static_cast<int>(std::strtol(argv[++i], &end, 10));
      if (*end != '\0' || options.repeat < 1) return Parsed::kBad;
    } else if (arg == "--cases" && has_value) {
      options.cases.clear();
      std::stringstream list(argv[++i]);
      for (std::string c; std::getline(list, c, ',');) options.cases.push_back(c);
    } else {
      return Parsed::kBad;
    }
  }
  return Parsed::kRun;
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
    const std::vector<bench::BenchSetting> settings =
        bench::selectCases(bench::planSweep(options.size), options.cases);
    bench::BenchContext context(options.reference);
    std::ofstream file;
    if (!options.out.empty()) {
      file.open(options.out);
      if (!file) throw std::runtime_error(options.out + ": cannot write");
    }
    std::ostream& out = options.out.empty() ? std::cout : file;
    bench::writeCsvHeader(out);
    deformable_sim::core::ProgressBar progress(static_cast<long>(settings.size()), stderr,
                                               "settings");
    for (size_t k = 0; k < settings.size(); ++k) {
      progress.update(static_cast<long>(k), bench::describe(settings[k]));
      for (const bench::BenchRow& row : bench::runSetting(settings[k], context, options.repeat)) {
        bench::writeCsvRow(row, out);
      }
      out.flush();
    }
    progress.finish();
  } catch (const std::exception& e) {
    std::cerr << "\nerror: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
