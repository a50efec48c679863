// Sorting by position makes the report read top to bottom however the reader visited
// the sections (it reads materials and stages first, to check names against them).
#include "scenario/scenario_diagnostics.hpp"

#include <algorithm>
#include <tuple>

#include "core/error.hpp"

namespace regodem {

void ScenarioDiagnostics::error(const SourceLocation& where, const std::string& message) {
  problems_.push_back({where, message});
}

void ScenarioDiagnostics::throw_if_any() const {
  if (problems_.empty()) return;
  std::vector<Problem> sorted = problems_;
  std::stable_sort(sorted.begin(), sorted.end(), [](const Problem& a, const Problem& b) {
    // Line 0 (no position: the whole file, or a --set override) sorts after the lines.
    const auto order = [](const SourceLocation& w) {
      return std::tuple(w.line == 0, w.line, w.column);
    };
    return order(a.where) < order(b.where);
  });
  std::string text;
  for (const Problem& problem : sorted) {
    if (!text.empty()) text += '\n';
    text += problem.where.describe() + ": " + problem.message;
  }
  throw InputError(text);
}

}  // namespace regodem
