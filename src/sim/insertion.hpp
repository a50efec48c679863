#pragma once
// Random, non-overlapping, dynamic insertion of particles into a region (by count, a
// rate over time, or all at once), or of a list of particles read from a file.
#include <cstddef>
#include <string>
#include <vector>

#include "core/particle_store.hpp"
#include "core/rng.hpp"
#include "sim/insertion_region.hpp"

namespace regodem {

class Simulation;

struct SizeClass {
  double radius_m = 0.0;
  double number_fraction = 1.0;  // share of the particle count
};

/// Initial temperature of inserted particles: value + gradient . (x - reference_point).
struct InitialTemperature {
  double value_K = 0.0;
  Vec3 gradient_K_per_m;
  Vec3 reference_point_m;
  double at(const Vec3& x_m) const { return value_K + dot(gradient_K_per_m, x_m - reference_point_m); }
};

struct Insertion {
  std::string name;
  InsertionRegion region;
  MaterialIndex material = 0;
  RegionTag tag = 0;
  double density_kg_per_m3 = 0.0;
  std::vector<SizeClass> sizes;
  std::size_t target_count = 0;
  double rate_per_s = 0.0;   // 0: all at the first attempt
  double interval_s = 0.0;   // between attempts when rate_per_s > 0
  bool allow_partial = false;  // ending short of target_count is no failure
  Vec3 velocity_m_per_s;
  InitialTemperature temperature;
  std::size_t stage = 0;
  std::vector<NewParticle> from_file;  // when not empty: these particles, placed as given
  std::vector<int> from_file_lines;    // their lines in the file, for messages

  // Progress (reset by start()).
  std::size_t inserted = 0;
  std::vector<std::size_t> inserted_per_class;
  double start_time_s = 0.0;
  std::size_t attempts = 0;
  int fruitless_attempts = 0;  // consecutive attempts that found no room
  bool finished = false;

  void start(double time_s);
  /// Simulated time of the next attempt.
  double next_attempt_s() const { return start_time_s + static_cast<double>(attempts) * interval_s; }
};

struct InsertionReport {
  std::size_t requested = 0;
  std::size_t placed = 0;
};

/// Makes the due attempt of an insertion: places up to the number the rate calls for
/// by now, each at a random spot that overlaps no particle and no wall. Returns what
/// it placed and what it wanted, so the caller can report a full region.
InsertionReport insert_due_particles(Simulation& sim, Insertion& insertion, Rng& rng);

}  // namespace regodem
