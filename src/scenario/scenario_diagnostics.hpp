#pragma once
// Collects every problem found in a scenario so that the user sees them all at once,
// each as "file:line:column: key.path: message".
#include <string>
#include <vector>

#include "scenario/scenario_spec.hpp"

namespace regodem {

class ScenarioDiagnostics {
 public:
  void error(const SourceLocation& where, const std::string& message);
  bool empty() const { return problems_.empty(); }
  std::size_t size() const { return problems_.size(); }

  /// Throws one InputError with a line per problem, in file order (problems in --set
  /// overrides last); does nothing when there are none.
  void throw_if_any() const;

 private:
  struct Problem {
    SourceLocation where;
    std::string message;
  };
  std::vector<Problem> problems_;
};

}  // namespace regodem
