#pragma once
// The fastest impact a run has seen, against its step (docs/physics.md, "Time step and
// integration"): of every touching contact closing at speed v, the one whose Hertz
// contact at that speed would be shortest, t_c = 2.87 (m*^2 / (R* E*^2 v))^(1/5)
// (sim/time_step.hpp). A closing contact's speed is largest at its first step, so this
// is the impact speed. Where it is resolved in fewer than ~10 steps its losses, and
// their heat, depend on the step.
#include <cstdint>

#include "sim/time_step.hpp"

namespace regodem {

/// Fewer steps than this in an impact's Hertz contact draws a warning (validate) and a
/// notice (run): LIGGGHTS' check/timestep/gran example warns above 0.1 of the Hertz time.
inline constexpr double kMinimumStepsPerImpact = 10.0;

struct ImpactRecord {
  double key = 0.0;                     // v R* E*^2 / m*^2 of the shortest contact; 0: none seen
  double approach_speed_m_per_s = 0.0;  // its v
  std::int32_t wall_body = -1;          // the wall it struck, -1 two particles
  double time_s = 0.0;                  // when

  bool seen() const { return key > 0.0; }
  double contact_time_s() const { return hertz_contact_time_from_key_s(key); }
  /// The larger key wins; on a tie the record kept first (so a merge in a fixed order is
  /// the same on any thread count).
  void consider(double candidate_key, double speed_m_per_s, std::int32_t wall) {
    if (candidate_key > key) key = candidate_key, approach_speed_m_per_s = speed_m_per_s, wall_body = wall;
  }
  void merge(const ImpactRecord& other) {
    if (other.key > key) *this = other;
  }
};

}  // namespace regodem
