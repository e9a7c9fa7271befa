// The numbers of ../shared/reference/results.csv (one row per number: case, element type, mesh,
// param, quantity, value, ...), looked up by what a comparison needs.
#pragma once

#include <string>
#include <vector>

namespace deformable_sim::bench {

class ReferenceResults {
 public:
  /// Reads results.csv. Throws std::runtime_error naming the file when it cannot be read.
  explicit ReferenceResults(const std::string& results_csv);

  /// The value of the row with this case ("A", "B", "C", "C2"), element type ("C3D4", "C3D20R"),
  /// mesh ("tetU_L2"), quantity ("tip_uz_mean_area") and a param that starts with `param_prefix`
  /// ("alpha=1 " selects "alpha=1 (P=8.33333 N)"; empty matches any). Throws std::out_of_range
  /// naming the row when there is none.
  double value(const std::string& case_id, const std::string& element, const std::string& mesh,
               const std::string& param_prefix, const std::string& quantity) const;

 private:
  struct Row {
    std::string case_id, element, mesh, param, quantity;
    double value;
  };
  std::vector<Row> rows_;
};

}  // namespace deformable_sim::bench
