#include "io/csv_table_reader.hpp"

#include <charconv>
#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "core/error.hpp"

namespace regodem {
namespace {

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

std::vector<std::string> split_row(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    cells.push_back(trimmed(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
    if (comma == std::string::npos) return cells;
    start = comma + 1;
  }
}

bool skipped(const std::string& line) {
  const std::string text = trimmed(line);
  return text.empty() || text.front() == '#';
}

}  // namespace

std::size_t CsvTable::column(const std::string& name) const {
  for (std::size_t c = 0; c < names.size(); ++c)
    if (names[c] == name) return c;
  std::string known;
  for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
  throw InputError(fmt::format("{}: no column '{}' (the columns are {})", path, name, known));
}

std::vector<double> CsvTable::numbers(const std::string& name) const {
  const std::size_t c = column(name);
  std::vector<double> values;
  values.reserve(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const std::string& text = rows[r][c];
    double value = 0.0;
    const char* end = text.data() + text.size();
    const auto [stop, error] = std::from_chars(text.data(), end, value);
    if (text.empty() || error != std::errc() || stop != end || !std::isfinite(value))
      throw InputError(fmt::format("{}:{}: column '{}': '{}' is not a number", path, line_numbers[r], name, text));
    values.push_back(value);
  }
  return values;
}

CsvTable read_csv_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("{}: cannot open the file", path));
  CsvTable table;
  table.path = path;
  std::string line;
  int line_number = 0;
  bool have_header = false;
  while (std::getline(in, line)) {
    ++line_number;
    if (skipped(line)) continue;
    std::vector<std::string> cells = split_row(line);
    if (!have_header) {
      for (const std::string& cell : cells) {
        // `name [unit]`: the unit is the text in the last brackets.
        std::string name = cell, unit;
        if (const auto open = cell.rfind('['); open != std::string::npos && cell.back() == ']') {
          name = trimmed(cell.substr(0, open));
          unit = cell.substr(open + 1, cell.size() - open - 2);
        }
        if (name.empty()) throw InputError(fmt::format("{}:{}: a column has no name", path, line_number));
        for (const std::string& known : table.names)
          if (known == name) throw InputError(fmt::format("{}:{}: column '{}' appears twice", path, line_number, name));
        table.names.push_back(name);
        table.units.push_back(unit);
      }
      have_header = true;
      continue;
    }
    if (cells.size() != table.names.size())
      throw InputError(fmt::format("{}:{}: {} values, but the header names {} columns", path, line_number,
                                   cells.size(), table.names.size()));
    table.rows.push_back(std::move(cells));
    table.line_numbers.push_back(line_number);
  }
  if (in.bad()) throw InputError(fmt::format("{}: cannot read the file", path));
  if (!have_header) throw InputError(fmt::format("{}: the file is empty (it needs a header line)", path));
  return table;
}

}  // namespace regodem
