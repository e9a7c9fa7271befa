#include "deformable_sim/bench/result_csv.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "deformable_sim/bench/csv_table.h"

namespace deformable_sim::bench {

namespace {

// Enough digits for errors down to 1e-12 and timings to 0.1 %; NaN as an empty field.
std::string number(double value, int digits = 7) {
  if (!std::isfinite(value)) return "";
  char text[32];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

}  // namespace

void writeCsvHeader(std::ostream& out) {
  out << "case,mesh,elements,warping,dt,substeps,solver,tolerance,max_iterations,error,"
         "error_definition,ms_per_step_median,iterations_mean,memory_bytes,error_same_mesh,value,"
         "reference_value,same_mesh_value,theory_value,ms_per_30hz_tick,nodes,linear_solves,"
         "converged,"
         "repeats\n";
}

void writeCsvRow(const BenchRow& row, std::ostream& out) {
  const BenchSetting& s = row.setting;
  const Comparison& c = row.comparison;
  const bool dynamic = s.dt_s > 0.0;
  const bool cg = s.solver.method == core::SolverSettings::Method::kConjugateGradient;
  out << c.case_name << "," << s.mesh << "," << row.elements << "," << (s.warping ? 1 : 0) << ","
      << (dynamic ? number(s.dt_s, 10) : "") << "," << (dynamic ? std::to_string(s.substeps) : "")
      << "," << solverName(s.solver) << "," << (cg ? number(s.solver.tolerance, 3) : "") << ","
      << (cg ? std::to_string(s.solver.max_iterations) : "") << "," << number(c.error) << ","
      << quoteCsvField(c.error_definition) << "," << number(row.ms_per_step_median, 5) << ","
      << number(row.iterations_mean, 5) << "," << row.memory_bytes << ","
      << number(c.error_same_mesh) << "," << number(c.value, 10) << ","
      << number(c.reference_value, 10) << "," << number(c.same_mesh_value, 10) << ","
      << number(c.theory_value, 10) << "," << number(row.ms_per_30hz_tick, 5) << "," << row.nodes
      << "," << number(row.linear_solves) << "," << (row.converged ? 1 : 0) << "," << row.repeats
      << "\n";
}

}  // namespace deformable_sim::bench
