#include "io/csv_time_series_writer.hpp"

#include <cerrno>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <system_error>

#include <fmt/format.h>

namespace regodem {

std::string csv_header_field(const SeriesColumn& column) {
  const std::string field = fmt::format("{} [{}]", column.name, column.unit);
  if (field.find_first_of(",\"\r\n") == std::string::npos) return field;
  std::string quoted = "\"";
  for (const char c : field) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  quoted += '"';
  return quoted;
}

CsvTimeSeriesWriter::CsvTimeSeriesWriter(std::filesystem::path path,
                                         const std::vector<SeriesColumn>& columns)
    : path_(std::move(path)), stream_(path_, std::ios::binary | std::ios::trunc),
      column_count_(columns.size()) {
  if (!stream_) {
    throw std::system_error(errno, std::generic_category(),
                            fmt::format("cannot create '{}'", path_.string()));
  }
  line_.clear();
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (i > 0) line_ += ',';
    line_ += csv_header_field(columns[i]);
  }
  write_line_and_flush(line_);
}

CsvTimeSeriesWriter::CsvTimeSeriesWriter(std::filesystem::path path, std::size_t column_count, std::uintmax_t bytes,
                                         std::size_t rows)
    : path_(std::move(path)), column_count_(column_count), rows_written_(rows), bytes_written_(bytes) {
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path_, error);
  if (error || size < bytes) {
    throw std::system_error(error ? error : std::make_error_code(std::errc::invalid_argument),
                            fmt::format("cannot continue '{}': it should hold at least {} bytes, it holds {}",
                                        path_.string(), bytes, error ? 0 : size));
  }
  // A file written by another version (other columns) must not be continued with rows
  // of this one's: refused before it is cut back.
  std::ifstream existing(path_, std::ios::binary);
  std::string header;
  std::getline(existing, header);
  std::size_t fields = 1;
  bool quoted = false;
  for (const char c : header) {
    if (c == '"') quoted = !quoted;
    if (c == ',' && !quoted) ++fields;
  }
  if (fields != column_count)
    throw std::system_error(std::make_error_code(std::errc::invalid_argument),
                            fmt::format("cannot continue '{}': its header has {} columns, this version writes {} (was "
                                        "the run started by another version of regodem?)",
                                        path_.string(), fields, column_count));
  existing.close();
  std::filesystem::resize_file(path_, bytes);
  stream_.open(path_, std::ios::binary | std::ios::app);
  if (!stream_) {
    throw std::system_error(errno, std::generic_category(), fmt::format("cannot open '{}'", path_.string()));
  }
}

void CsvTimeSeriesWriter::write_row(std::span<const double> values) {
  if (values.size() != column_count_) {
    throw std::invalid_argument(fmt::format("time-series row has {} values for {} columns of '{}'",
                                            values.size(), column_count_, path_.string()));
  }
  line_.clear();
  auto out = std::back_inserter(line_);
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i > 0) line_ += ',';
    fmt::format_to(out, "{}", values[i]);  // shortest round-trip representation
  }
  write_line_and_flush(line_);
  ++rows_written_;
}

void CsvTimeSeriesWriter::write_line_and_flush(std::string_view line) {
  stream_.write(line.data(), static_cast<std::streamsize>(line.size()));
  stream_.put('\n');
  stream_.flush();
  bytes_written_ += line.size() + 1;
  if (!stream_) {
    throw std::system_error(errno, std::generic_category(),
                            fmt::format("cannot write '{}'", path_.string()));
  }
}

}  // namespace regodem
