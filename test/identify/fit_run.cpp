#include "fit_run.h"

#include <gtest/gtest.h>
#include <ros/time.h>

#include <cmath>
#include <cstdio>
#include <fstream>

namespace deformable_sim::test {

FitRun runFit(const std::filesystem::path& directory, const std::string& fit_text,
              int max_iterations, const std::string& plot, bool residuals) {
  ros::Time::init();
  const std::filesystem::path fit_file = directory / "fit.yaml";
  std::ofstream(fit_file) << fit_text;
  ros_layer::IdentifyOptions options;
  options.fit_file = fit_file.string();
  options.threads = 2;
  options.max_iterations = max_iterations;
  options.plot = plot;
  options.plot_residuals = residuals;
  options.plot_script = DEFORMABLE_SIM_SOURCE_DIR "/scripts/plot_identify.py";
  char* text = nullptr;
  std::size_t size = 0;
  std::FILE* out = open_memstream(&text, &size);
  FitRun run;
  try {
    run.result = ros_layer::identify(options, out);
  } catch (const std::exception& e) {
    run.refusal = e.what();
  }
  std::fclose(out);
  run.printed.assign(text, size);
  std::free(text);
  return run;
}

void expectFitted(const FitRun& run, const std::vector<double>& truth,
                  const std::vector<double>& relative) {
  SCOPED_TRACE(run.printed + run.refusal);
  EXPECT_EQ(run.result.exit_code, 0);
  const identify::FitResult& fit = run.result.fit;
  ASSERT_EQ(fit.values.size(), truth.size());
  for (std::size_t i = 0; i < truth.size(); ++i) {
    EXPECT_NEAR(fit.values[i], truth[i], relative[i] * truth[i]);
    EXPECT_LE(std::abs(fit.values[i] - truth[i]), 3.0 * fit.standard_deviations[i]);
  }
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

}  // namespace deformable_sim::test
