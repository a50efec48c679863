#pragma once
// What `regodem calibrate` is asked to do (docs/calibration.md, "The calibration file"):
// which scenario to run, against which reference, over which factors, which responses
// to read from each run's summary.json, and how to solve the fitted surfaces for the
// reference's values. Plain data: src/scenario/calibration_reader.cpp reads it from YAML.
#include <optional>
#include <string>
#include <vector>

#include "doe/central_composite_design.hpp"

namespace regodem::doe {

/// A value read from the reference's summary.json and given to every other run as
/// `--set SET_PATH="VALUE UNIT"` (e.g. the reference's end time as a stage duration).
struct PassOn {
  std::string from_json_path;  // into summary.json, e.g. "stages.heat.end_time_s"
  std::string set_path;        // scenario key path, e.g. "stages.heat.duration"
  std::string unit;            // appended to a number; may be empty
  std::string where;           // "file:line:column: key" for messages
};

/// A factor: a scenario value that the design varies (`--set SET_PATH="VALUE UNIT"`).
struct CalibrationFactor {
  DesignFactor design;   // name, unit, centre, step
  std::string set_path;  // e.g. "walls.sieve.thermal.specific_heat"
  // The value as the scenario takes it, `{}` standing for the number: "[0, 0, -{} mm/s]"
  // for a feed that is a velocity vector. Empty: "NUMBER UNIT".
  std::string value_template;
};

/// A response read from summary.json, and the value the calibration wants of it.
struct CalibrationResponse {
  std::string name;
  std::string unit;       // for headers and reports; may be empty
  std::string json_path;  // in each run's summary.json, e.g. "measurements.bands.sieve.final.T_d_K"
  std::optional<std::string> target_reference_path;  // in the reference's summary.json
  std::optional<double> target_value;                 // or a given number
  std::string terms;      // as `regodem fit --terms`; empty: the full quadratic
  std::string where;
};

enum class CalibrationSolveMode {
  simultaneous,  // every target together (as many as free factors), Newton from a grid of starts
  sequential,    // one response for one factor after another, the others held (the paper's way)
};

/// One step of a sequential solve: `response` reaches its target through `factor`.
struct CalibrationSolveStep {
  std::string response;
  std::string factor;
};

struct CalibrationSolve {
  CalibrationSolveMode mode = CalibrationSolveMode::simultaneous;
  /// Factors held at a value (sequential: until a step solves for them); a factor not
  /// held and not solved stays at its design centre.
  std::vector<std::pair<std::string, double>> fixed;
  std::vector<CalibrationSolveStep> steps;  // sequential only
};

struct CalibrationSpec {
  std::string file;  // the calibration file, as given

  std::string scenario;  // absolute; run at every design point and at the solution
  struct Reference {
    std::string scenario;          // absolute
    std::vector<std::string> set;  // extra --set for the reference only
    std::vector<PassOn> pass_on;
  } reference;
  std::vector<std::string> set;  // --set for every run, the reference included (first)

  std::vector<CalibrationFactor> factors;
  CcdOptions design;  // standard order: the runs are deterministic, randomising buys nothing
  std::vector<CalibrationResponse> responses;
  CalibrationSolve solve;

  int processes = 0;        // runs at once; 0: the cores / threads_per_run
  int threads_per_run = 1;  // --threads of each run
  int ranks_per_run = 1;    // > 1: each run under `mpirun -np ranks_per_run` (docs/mpi.md)
};

}  // namespace regodem::doe
