#pragma once
// Particle data as a structure of arrays: one contiguous array per field, so the force
// and integration loops stream through only what they use. Every field is listed once,
// with its name, unit and role in a distributed run, in for_each_described_field();
// resize, permutation (spatial sorting), removal and checkpoints are driven by that
// list, so a field added there is carried everywhere.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/vec3.hpp"

namespace regodem {

using ParticleId = std::uint32_t;
using MaterialIndex = std::uint16_t;
using RegionTag = std::uint16_t;

struct NewParticle {
  Vec3 position_m;
  Vec3 velocity_m_per_s;
  Vec3 angular_velocity_rad_per_s;
  double radius_m = 0.0;
  double density_kg_per_m3 = 0.0;
  MaterialIndex material = 0;
  RegionTag region = 0;
  double temperature_K = 0.0;
};

/// What the field table says of a field.
struct ParticleField {
  const char* name;
  const char* unit;  // "-": none
  // Travels with a particle that moves to another rank's domain: everything but what the
  // next force pass computes afresh (torque, heat flow). The force travels, and goes to
  // the ghosts: the neighbour build reads it (a particle's half of the skin, NeighborSkin),
  // which must be the same on every rank that holds the particle.
  bool migrates;
  // Copied to the ghost images of a particle near another rank's domain: what a contact
  // with it reads.
  bool ghosts_need;
  // Of those, what changes in a step, sent to the ghosts every step between builds.
  bool ghosts_refresh;
};

class ParticleStore {
 public:
  // Per-particle fields (shape: size()).
  std::vector<ParticleId> id;           // global id, stable across sorting, restarts and (later) ranks
  std::vector<double> radius_m;
  std::vector<double> mass_kg;
  std::vector<double> inv_mass_per_kg;  // 0 for a particle held fixed
  std::vector<double> inv_inertia;      // 1/(2/5 m R^2); 0 locks rotation
  std::vector<Vec3> position_m;
  std::vector<Vec3> velocity_m_per_s;
  std::vector<Vec3> angular_velocity_rad_per_s;
  std::vector<Vec3> force_N;
  std::vector<Vec3> torque_N_m;
  std::vector<MaterialIndex> material;
  std::vector<RegionTag> region;
  std::vector<double> temperature_K;
  std::vector<double> heat_flow_W;            // net heat into the particle, summed in the contact pass
  std::vector<double> conductivity_W_per_mK;  // k at the particle's temperature
  // Thermal history (measure/thermal_history.hpp), kept while the run tracks it: the
  // highest temperature reached (from the inserted one) and the time spent above the
  // threshold.
  std::vector<double> peak_temperature_K;
  std::vector<double> time_above_threshold_s;

  /// Calls f(const ParticleField&, vector&) for every per-particle field: the one list
  /// of fields (the field table).
  template <class F>
  void for_each_described_field(F&& f) {
    f(ParticleField{"id", "-", true, true, false}, id);
    f(ParticleField{"radius", "m", true, true, false}, radius_m);
    f(ParticleField{"mass", "kg", true, false, false}, mass_kg);
    f(ParticleField{"inverse_mass", "1/kg", true, true, false}, inv_mass_per_kg);
    f(ParticleField{"inverse_inertia", "1/(kg m^2)", true, true, false}, inv_inertia);
    f(ParticleField{"position", "m", true, true, true}, position_m);
    f(ParticleField{"velocity", "m/s", true, true, true}, velocity_m_per_s);
    f(ParticleField{"angular_velocity", "rad/s", true, true, true}, angular_velocity_rad_per_s);
    f(ParticleField{"force", "N", true, true, false}, force_N);
    f(ParticleField{"torque", "N m", false, false, false}, torque_N_m);
    f(ParticleField{"material", "-", true, true, false}, material);
    f(ParticleField{"region", "-", true, false, false}, region);
    f(ParticleField{"temperature", "K", true, true, true}, temperature_K);
    f(ParticleField{"heat_flow", "W", false, false, false}, heat_flow_W);
    f(ParticleField{"conductivity", "W/(m K)", true, true, true}, conductivity_W_per_mK);
    f(ParticleField{"peak_temperature", "K", true, false, false}, peak_temperature_K);
    f(ParticleField{"time_above_threshold", "s", true, false, false}, time_above_threshold_s);
  }
  /// Calls f(vector&) for every per-particle field.
  template <class F>
  void for_each_field(F&& f) {
    for_each_described_field([&](const ParticleField&, auto& field) { f(field); });
  }

  std::size_t size() const { return id.size(); }
  bool empty() const { return id.empty(); }
  /// Next global id to hand out; ids are never reused.
  ParticleId next_id() const { return next_id_; }
  void set_next_id(ParticleId next) { next_id_ = next; }

  /// Appends a solid sphere; returns its local index.
  std::size_t add(const NewParticle& p);
  /// Reorders all fields so that new index k holds old index order[k].
  void permute(const std::vector<std::uint32_t>& order, int threads = 1);
  /// Removes the particles whose flag is set, keeping the order of the rest.
  void remove_if(const std::vector<char>& remove_flag);
  void reserve(std::size_t n);

 private:
  ParticleId next_id_ = 0;
};

}  // namespace regodem
