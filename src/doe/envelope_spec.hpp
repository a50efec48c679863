#pragma once
// What `regodem envelope` is asked to do (docs/drilling-heat.md, "The operating
// envelope"): a central composite design over scenario values (feed, speed, ...), each
// point a drilling run; responses read from each run's outputs; response surfaces fitted;
// a map of one response over two factors with its threshold contour. Plain data:
// src/scenario/calibration_reader.cpp reads it from YAML.
#include <optional>
#include <string>
#include <vector>

#include "doe/calibration_spec.hpp"

namespace regodem::doe {

/// How a response reduces a column of one of the run's CSV files.
enum class SeriesReduction { max, min, mean, final };

struct EnvelopeResponse {
  std::string name;
  std::string unit;       // for headers and reports; may be empty
  std::string json_path;  // in the run's summary.json, or empty and:
  std::string series_file;    // a CSV the run wrote, relative to its folder ("time_series.csv")
  std::string series_column;  // a column of it, without its unit ("drill.thrust")
  SeriesReduction reduction = SeriesReduction::max;  // over the rows that are numbers (nan skipped)
  std::string terms;  // as `regodem fit --terms`; empty: the full quadratic
  std::string where;
};

/// The map: `response` over factors `x` and `y` (the others at their centres) on a grid
/// spanning the design, with the contour where it equals `threshold`.
struct EnvelopeMap {
  std::string x, y, response;
  double threshold = 0.0;
  int grid = 61;  // points along each axis
  std::string where;
};

struct EnvelopeSpec {
  std::string file;      // the envelope file, as given
  std::string scenario;  // absolute; run at every design point
  std::vector<std::string> set;  // --set for every run
  std::vector<CalibrationFactor> factors;
  CcdOptions design;
  std::vector<EnvelopeResponse> responses;
  EnvelopeMap map;
  int processes = 0;        // runs at once; 0: the cores / threads_per_run
  int threads_per_run = 1;  // --threads of each run
  int ranks_per_run = 1;    // > 1: each run under `mpirun -np ranks_per_run` (docs/mpi.md)
};

}  // namespace regodem::doe
