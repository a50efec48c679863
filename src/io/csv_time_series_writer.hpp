#pragma once
// The time series of a run as CSV: a header row naming each column with its unit
// ("time [s]"), then one row per sample. A CSV is a stream that grows during the run,
// so rows are appended and flushed as they come (a reader can follow a long run)
// rather than written whole at the end.
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sim/run_observer.hpp"

namespace regodem {

/// "name [unit]", quoted as RFC 4180 asks when it holds a comma, quote or newline.
std::string csv_header_field(const SeriesColumn& column);

class CsvTimeSeriesWriter {
 public:
  /// Creates (or truncates) the file and writes the header row; throws
  /// std::system_error naming the file if it cannot be written.
  CsvTimeSeriesWriter(std::filesystem::path path, const std::vector<SeriesColumn>& columns);
  /// Continues a file this writer wrote before (a resumed run): cuts it back to its
  /// first `bytes` (header and `rows` rows, as bytes_written() said then), dropping
  /// rows written after that point, and appends from there. Throws std::system_error
  /// naming the file when it is shorter than that or cannot be written.
  CsvTimeSeriesWriter(std::filesystem::path path, std::size_t column_count, std::uintmax_t bytes, std::size_t rows);

  /// Appends one row, numbers in their shortest form that reads back to the same
  /// double; throws std::invalid_argument when the row has the wrong length.
  void write_row(std::span<const double> values);

  std::size_t column_count() const { return column_count_; }
  std::size_t rows_written() const { return rows_written_; }
  /// Length of the file so far (header and rows), for checkpoints.
  std::uintmax_t bytes_written() const { return bytes_written_; }
  const std::filesystem::path& path() const { return path_; }

 private:
  void write_line_and_flush(std::string_view line);

  std::filesystem::path path_;
  std::ofstream stream_;
  std::size_t column_count_ = 0;
  std::size_t rows_written_ = 0;
  std::uintmax_t bytes_written_ = 0;
  std::string line_;  // reused between rows
};

}  // namespace regodem
