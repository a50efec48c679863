#pragma once
// Central composite designs (Box & Wilson 1951; Montgomery, Design and Analysis of
// Experiments, 8th ed., section 11.4.2): a two-level factorial (full, or a half
// fraction for k >= 5), 2k axial points at ±α on each axis, and centre points. Coded
// value x and actual value: actual = centre + x · step.
#include <cstdint>
#include <string>
#include <vector>

namespace regodem::doe {

struct DesignFactor {
  std::string name;
  std::string unit;     // may be empty; carried into CSV headers as `name [unit]`
  double centre = 0.0;  // actual value at coded 0
  double step = 1.0;    // actual change per coded unit (> 0)

  double actual(double coded) const { return centre + coded * step; }
};

enum class AlphaKind {
  rotatable,  // α = n_F^(1/4), n_F the number of factorial points (Box & Hunter 1957)
  face,       // α = 1: axial points on the faces of the cube
  given,      // α as given
};

enum class RunOrder { standard, random };

struct CcdOptions {
  AlphaKind alpha_kind = AlphaKind::rotatable;
  double alpha = 0.0;          // used when alpha_kind == given (> 0)
  int centre_points = 1;       // >= 0
  bool half_fraction = false;  // 2^(k−1) factorial with I = AB…K (resolution k), k >= 5
  RunOrder order = RunOrder::standard;
  std::uint64_t seed = 1;  // for RunOrder::random
};

enum class PointType { factorial, axial, centre };

const char* point_type_name(PointType type);

struct DesignPoint {
  int standard_order = 0;  // 1-based position in standard order
  PointType type = PointType::centre;
  std::vector<double> coded;   // one per factor
  std::vector<double> actual;  // one per factor
};

struct CentralCompositeDesign {
  std::vector<DesignFactor> factors;
  double alpha = 0.0;
  int factorial_points = 0;  // n_F
  int axial_points = 0;      // 2k
  int centre_points = 0;
  std::vector<DesignPoint> runs;  // in run order (standard, or shuffled)
};

/// Builds the design. Standard order: factorial points in Yates order (first factor
/// changing fastest), then axial points (−α, +α for each factor in turn), then the
/// centre points. A random order is a Fisher–Yates shuffle with regodem::Rng(seed), so a
/// seed gives the same order on every platform. Throws InputError for bad options.
CentralCompositeDesign make_central_composite_design(const std::vector<DesignFactor>& factors,
                                                     const CcdOptions& options);

/// The rotatable α for a factorial part of n_F points: n_F^(1/4).
double rotatable_alpha(int factorial_points);

/// `name [unit]` as RegoDEM's CSV headers write it (`name` without a unit).
std::string header_name(const DesignFactor& factor);

/// The design as CSV (`regodem doe ccd`, docs/calibration.md): run, std_order,
/// point_type, NAME_coded per factor, then each factor's actual value under
/// header_name; numbers in the shortest form that reads back to the same double.
std::string design_csv(const CentralCompositeDesign& design);

}  // namespace regodem::doe
