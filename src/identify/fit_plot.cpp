#include "deformable_sim/identify/fit_plot.h"

#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace deformable_sim::identify {

namespace {

const char* componentName(const ObservationSpec& spec, int k) {
  static const char* position[] = {"x (m)", "y (m)", "z (m)"};
  static const char* wrench[] = {"force x (N)",    "force y (N)",    "force z (N)",
                                 "torque x (N m)", "torque y (N m)", "torque z (N m)"};
  return spec.kind == ObservationSpec::Kind::kFrame ? position[k] : wrench[k];
}

// Quoted for the shell: single quotes, with any inside closed and escaped.
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

void writeFitTable(const Experiment& experiment, const std::vector<double>& guess,
                   const std::vector<double>& fitted, const std::string& csv_path) {
  const std::vector<SimulatedSeries> first = experiment.simulate(guess);
  const std::vector<SimulatedSeries> last = experiment.simulate(fitted);
  std::ofstream csv(csv_path);
  csv << "observation,component,time,measured,guess,fitted\n";
  const RecordedExperiment& recorded = experiment.recorded();
  for (std::size_t o = 0; o < recorded.observations.size(); ++o) {
    const ObservationSpec& spec = recorded.observations[o];
    const std::string name = spec.key + " " + spec.topic;
    const MeasuredSeries& measured = recorded.measured[o];
    for (std::size_t s = 0; s < measured.times.size(); ++s) {
      const double t = measured.times[s];
      const Eigen::VectorXd a = experiment.predicted(o, s, first[o], guess),
                            b = experiment.predicted(o, s, last[o], fitted);
      for (Eigen::Index k = 0; k < a.size(); ++k) {
        csv << name << "," << componentName(spec, static_cast<int>(k)) << "," << t << ","
            << measured.values[s][k] << "," << a[k] << "," << b[k] << "\n";
      }
    }
  }
  if (!csv) throw std::runtime_error("cannot write '" + csv_path + "'");
}

void plotFit(const Experiment& experiment, const std::vector<double>& guess,
             const std::vector<double>& fitted, const std::string& png_path,
             const std::string& script, bool residuals) {
  const std::string csv_path = png_path + ".csv";
  writeFitTable(experiment, guess, fitted, csv_path);
  const std::string command = "/usr/bin/python3 " + quoted(script) +
                              (residuals ? " --residuals " : " ") + quoted(csv_path) + " " +
                              quoted(png_path);
  if (std::system(command.c_str()) != 0)
    throw std::runtime_error("--plot: " + script + " could not draw " + png_path);
}

}  // namespace deformable_sim::identify
