// SourceLocation::describe, the prefix of every scenario error message.
#include <fmt/format.h>

#include "scenario/scenario_spec.hpp"

namespace regodem {

std::string SourceLocation::describe() const {
  std::string text = file;
  if (line > 0) text += column > 0 ? fmt::format(":{}:{}", line, column) : fmt::format(":{}", line);
  if (!key.empty()) text += (text.empty() ? "" : ": ") + key;
  return text;
}

}  // namespace regodem
