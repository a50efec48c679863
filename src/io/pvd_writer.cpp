#include "io/pvd_writer.hpp"

#include <stdexcept>

#include <fmt/format.h>

#include "io/atomic_file.hpp"

namespace regodem {

void PvdCollection::restore(std::vector<Entry> entries) {
  entries_ = std::move(entries);
  write_file_atomically(path_, to_string());
}

void PvdCollection::add(double time_s, const std::string& relative_file) {
  if (!entries_.empty() && time_s < entries_.back().time_s)
    throw std::invalid_argument(fmt::format("{}: time {:.17g} s comes before the previous {:.17g} s",
                                            path_.string(), time_s, entries_.back().time_s));
  if (relative_file.find_first_of("\"<>&") != std::string::npos)
    throw std::invalid_argument(fmt::format("{}: unusable file name '{}'", path_.string(), relative_file));
  entries_.push_back({time_s, relative_file});
  write_file_atomically(path_, to_string());
}

std::string PvdCollection::to_string() const {
  std::string xml =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n";
  // 17 significant digits: the time reads back as the same double.
  for (const Entry& e : entries_)
    xml += fmt::format("    <DataSet timestep=\"{:.17g}\" group=\"\" part=\"0\" file=\"{}\"/>\n", e.time_s, e.file);
  xml += "  </Collection>\n</VTKFile>\n";
  return xml;
}

}  // namespace regodem
