#pragma once
// Error types that reach the user. InputError: the scenario or command line is wrong
// (nothing has run). SimulationError: the run went wrong (blow-up, escape) and says
// where and when, with a suggestion.
#include <stdexcept>
#include <string>

namespace regodem {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class SimulationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace regodem
