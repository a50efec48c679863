#include "io/csv_time_series_writer.hpp"

#include <cerrno>
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
  if (!stream_) {
    throw std::system_error(errno, std::generic_category(),
                            fmt::format("cannot write '{}'", path_.string()));
  }
}

}  // namespace regodem
