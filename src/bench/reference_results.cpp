#include "deformable_sim/bench/reference_results.h"

#include <stdexcept>

#include "deformable_sim/bench/csv_table.h"

namespace deformable_sim::bench {

ReferenceResults::ReferenceResults(const std::string& results_csv) {
  const CsvTable table = readCsvTable(results_csv);
  const int case_column = table.column("case"), element = table.column("element_type"),
            mesh = table.column("mesh"), param = table.column("param"),
            quantity = table.column("quantity"), value = table.column("value");
  for (const auto& row : table.rows) {
    rows_.push_back({row[case_column], row[element], row[mesh], row[param], row[quantity],
                     std::stod(row[value])});
  }
}

double ReferenceResults::value(const std::string& case_id, const std::string& element,
                               const std::string& mesh, const std::string& param_prefix,
                               const std::string& quantity) const {
  for (const Row& row : rows_) {
    if (row.case_id == case_id && row.element == element && row.mesh == mesh &&
        row.quantity == quantity && row.param.rfind(param_prefix, 0) == 0) {
      return row.value;
    }
  }
  throw std::out_of_range("results.csv has no row " + case_id + "," + element + "," + mesh + ",'" +
                          param_prefix + "...'," + quantity);
}

}  // namespace deformable_sim::bench
