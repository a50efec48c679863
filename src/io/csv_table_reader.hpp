#pragma once
// Reads a table of runs: a CSV file whose first (non-comment) line names the columns,
// as `name [unit]` (what RegoDEM writes) or a plain `name`. Cells are kept as text and
// converted when a column is asked for as numbers, so text columns (a design's point
// type) may sit beside numeric ones. Lines starting with '#' and blank lines are skipped;
// quoted cells are not supported.
#include <string>
#include <vector>

namespace regodem {

struct CsvTable {
  std::string path;
  std::vector<std::string> names;  // the header without units
  std::vector<std::string> units;  // "" where the header gives none
  std::vector<std::vector<std::string>> rows;
  std::vector<int> line_numbers;  // file line of each row, for messages

  /// The column's index; throws InputError naming the columns there are.
  std::size_t column(const std::string& name) const;
  /// The column as numbers; throws InputError naming file, line and cell if one is not a number.
  std::vector<double> numbers(const std::string& name) const;
};

/// Throws InputError if the file cannot be read, has no header, repeats a column name, or
/// has a row with more or fewer cells than the header.
CsvTable read_csv_table(const std::string& path);

}  // namespace regodem
