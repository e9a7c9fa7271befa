// Comma-separated tables as RFC 4180 writes them: fields with commas, quotes or line breaks are
// quoted, quotes inside doubled. The reference results and the bench's own output both need this
// (their notes and error definitions contain commas).
#pragma once

#include <string>
#include <vector>

namespace deformable_sim::bench {

/// The fields of one line (no line breaks inside quoted fields: none of our tables has any).
std::vector<std::string> splitCsvLine(const std::string& line);

/// `field` as a CSV field: quoted when it contains a comma, a quote or a line break.
std::string quoteCsvField(const std::string& field);

/// A whole table: the header and the rows, every row as long as the header.
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;

  /// Index of the column of that name; throws std::out_of_range naming it when there is none.
  int column(const std::string& name) const;
};

/// Reads a table with one header line; lines that are empty or start with '#' are skipped.
/// Throws std::runtime_error naming the file (unreadable) or the line (wrong number of fields).
CsvTable readCsvTable(const std::string& path);

}  // namespace deformable_sim::bench
