#include "io/particle_csv_reader.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "io/text_words.hpp"

namespace regodem {
namespace {

std::vector<std::string> split_row(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) {
    const auto first = cell.find_first_not_of(" \t\r");
    const auto last = cell.find_last_not_of(" \t\r");
    cells.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
  }
  return cells;
}

}  // namespace

std::vector<ParticleRecord> read_particle_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("{}: cannot open the particle file", path));
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.find_first_not_of(" \t\r") != std::string::npos && line[0] != '#') break;
  }
  const std::vector<std::string> header = split_row(line);
  enum Column { x, y, z, radius, vx, vy, vz, temperature, count };
  const std::array<const char*, count> names = {"x", "y", "z", "radius", "vx", "vy", "vz", "temperature"};
  std::array<int, count> where{};
  where.fill(-1);
  for (std::size_t c = 0; c < header.size(); ++c) {
    bool known = false;
    for (int k = 0; k < count; ++k) {
      if (header[c] != names[k]) continue;
      if (where[k] >= 0)
        throw InputError(fmt::format("{}:{}: the column '{}' appears twice (columns {} and {}); which one is meant?",
                                     path, line_number, names[k], where[k] + 1, c + 1));
      where[k] = static_cast<int>(c);
      known = true;
    }
    if (!known)
      throw InputError(fmt::format("{}:{}: unknown column '{}' (expected x, y, z, radius, and optionally vx, vy, vz, "
                                   "temperature; SI units)",
                                   path, line_number, printable_excerpt(header[c])));
  }
  for (int k : {x, y, z, radius})
    if (where[k] < 0)
      throw InputError(fmt::format("{}:{}: the header lacks the column '{}'", path, line_number, names[k]));

  std::vector<ParticleRecord> records;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    const std::vector<std::string> cells = split_row(line);
    if (cells.size() != header.size())
      throw InputError(fmt::format("{}:{}: {} values, but the header names {} columns", path, line_number,
                                   cells.size(), header.size()));
    auto value = [&](int k) {
      const std::string& text = cells[where[k]];
      std::size_t used = 0;
      double v = 0.0;
      try {
        v = std::stod(text, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != text.size() || text.empty() || !std::isfinite(v))
        throw InputError(
            fmt::format("{}:{}: column '{}': '{}' is not a number", path, line_number, names[k], printable_excerpt(text)));
      return v;
    };
    ParticleRecord r;
    r.line = line_number;
    r.position_m = {value(x), value(y), value(z)};
    r.radius_m = value(radius);
    if (r.radius_m <= 0.0)
      throw InputError(fmt::format("{}:{}: radius must be positive, got {}", path, line_number, r.radius_m));
    if (where[vx] >= 0) r.velocity_m_per_s.x = value(vx);
    if (where[vy] >= 0) r.velocity_m_per_s.y = value(vy);
    if (where[vz] >= 0) r.velocity_m_per_s.z = value(vz);
    if (where[temperature] >= 0) r.temperature_K = value(temperature), r.has_temperature = true;
    records.push_back(r);
  }
  if (records.empty()) throw InputError(fmt::format("{}: no particles in the file", path));
  return records;
}

}  // namespace regodem
