#pragma once
// The shipped scenario files as text for tests that change a line or two of them: read,
// without their settled bed, with one probe grain in its place.
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

namespace regodem {

namespace fs = std::filesystem;

inline std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The text without its `initial_state:` line (a one-line map in these files). Plain
/// string work: std::regex trips GCC 12's -Wmaybe-uninitialized under the sanitizers.
inline std::string without_initial_state(std::string text) {
  const std::size_t start = text.find("\ninitial_state:");
  if (start == std::string::npos) return text;
  const std::size_t end = text.find('\n', start + 1);
  return text.erase(start, end - start);
}

/// Every `from` in the text replaced by `to`.
inline std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

/// The tiny drilling file with one probe grain in place of its bed; `edit` changes its text first.
inline std::string tiny_drill_text(const std::function<std::string(std::string)>& edit, const fs::path& csv) {
  const fs::path source = fs::path(REGODEM_SOURCE_DIR) / "scenarios" / "paper" / "tiny" / "drill-sieve.yaml";
  std::string text = edit(without_initial_state(read_text(source)));
  {
    std::ofstream out(csv);
    out << "x,y,z,radius\n0,0,0.005,0.001\n";
  }
  return text + "\ninsertions:\n  - {name: probe, material: regolith, file: " + csv.string() +
         ", temperature: -196 degC}\n";
}

}  // namespace regodem
