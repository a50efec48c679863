// Particles as bytes for messages between ranks (src/parallel/particle_transfer.hpp):
// what the field table marks as travelling arrives bit for bit, the rest starts at 0.
#include <gtest/gtest.h>

#include <cstring>
#include <set>
#include <string>

#include "core/error.hpp"
#include "core/rng.hpp"
#include "parallel/particle_transfer.hpp"

namespace regodem {
namespace {

ParticleStore random_store(std::size_t count) {
  Rng rng(23);
  ParticleStore store;
  store.set_next_id(1000);
  for (std::size_t k = 0; k < count; ++k) {
    NewParticle p;
    p.position_m = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(0, 1)};
    p.velocity_m_per_s = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
    p.angular_velocity_rad_per_s = {rng.uniform(-9, 9), rng.uniform(-9, 9), rng.uniform(-9, 9)};
    p.radius_m = rng.uniform(1e-4, 1e-3);
    p.density_kg_per_m3 = 3100.0;
    p.material = static_cast<MaterialIndex>(k % 3);
    p.region = static_cast<RegionTag>(k % 5);
    p.temperature_K = rng.uniform(100, 200);
    store.add(p);
  }
  // Every field holds something other than 0, the computed ones too.
  for (std::size_t k = 0; k < count; ++k) {
    const double x = static_cast<double>(k);
    store.force_N[k] = {1.0 + x, 2.0, 3.0};
    store.torque_N_m[k] = {4.0, 5.0 + x, 6.0};
    store.heat_flow_W[k] = 7.0 + x;
    store.conductivity_W_per_mK[k] = 0.5 + x;
    store.peak_temperature_K[k] = 300.0 + x;
    store.time_above_threshold_s[k] = 0.25 * x;
  }
  return store;
}

// Whether field `name` of particle a of `x` and b of `y` hold the same bytes.
bool same_field(ParticleStore& x, std::size_t a, ParticleStore& y, std::size_t b, const std::string& name) {
  const void* pa = nullptr;
  const void* pb = nullptr;
  std::size_t size = 0;
  x.for_each_described_field([&](const ParticleField& f, auto& v) {
    if (name == f.name) pa = &v[a], size = sizeof(v[a]);
  });
  y.for_each_described_field([&](const ParticleField& f, auto& v) {
    if (name == f.name) pb = &v[b];
  });
  return pa && pb && std::memcmp(pa, pb, size) == 0;
}

bool is_zero_field(ParticleStore& x, std::size_t a, const std::string& name) {
  bool zero = false;
  x.for_each_described_field([&](const ParticleField& f, auto& v) {
    if (name != f.name) return;
    using T = typename std::remove_reference_t<decltype(v)>::value_type;
    const T none{};
    zero = std::memcmp(&v[a], &none, sizeof(T)) == 0;
  });
  return zero;
}

void expect_carried(ParticleTransfer kind) {
  ParticleStore from = random_store(50);
  const std::vector<std::uint32_t> picked = {7, 3, 49, 0, 21};
  std::vector<std::byte> bytes;
  pack_particles(from, picked, kind, bytes);
  ParticleStore into = random_store(2);  // appended after what is there
  EXPECT_EQ(unpack_particles(bytes, kind, into), bytes.size());
  ASSERT_EQ(into.size(), 2 + picked.size());
  std::set<std::string> carried, left;
  from.for_each_described_field([&](const ParticleField& f, auto&) {
    (kind == ParticleTransfer::migration ? f.migrates : f.ghosts_need) ? carried.insert(f.name) : left.insert(f.name);
  });
  EXPECT_TRUE(carried.count("position") && carried.count("id"));
  for (std::size_t k = 0; k < picked.size(); ++k) {
    for (const std::string& name : carried) EXPECT_TRUE(same_field(from, picked[k], into, 2 + k, name)) << name;
    for (const std::string& name : left) EXPECT_TRUE(is_zero_field(into, 2 + k, name)) << name;
  }
}

TEST(ParticleTransfer, AMigratingParticleTakesEveryFieldButThoseTheNextPassComputes) {
  expect_carried(ParticleTransfer::migration);
}

TEST(ParticleTransfer, AGhostCarriesWhatAContactReads) { expect_carried(ParticleTransfer::ghost); }

TEST(ParticleTransfer, AGhostUpdateOverwritesWhatChangesInAStepAndNothingElse) {
  ParticleStore from = random_store(50);
  const std::vector<std::uint32_t> picked = {7, 3, 49};
  std::vector<std::byte> bytes;
  pack_particles(from, picked, ParticleTransfer::ghost_refresh, bytes);
  ParticleStore into = random_store(6), before = random_store(6);
  const std::vector<std::uint32_t> places = {4, 0, 5};
  EXPECT_EQ(unpack_particles_at(bytes, ParticleTransfer::ghost_refresh, into, places), bytes.size());
  ASSERT_EQ(into.size(), 6u);
  std::set<std::string> refreshed, kept;
  from.for_each_described_field([&](const ParticleField& f, auto&) {
    (f.ghosts_refresh ? refreshed : kept).insert(f.name);
    EXPECT_TRUE(!f.ghosts_refresh || f.ghosts_need) << f.name << ": refreshed but not in a new ghost";
  });
  for (const char* changes : {"position", "velocity", "angular_velocity", "temperature", "conductivity"})
    EXPECT_TRUE(refreshed.count(changes)) << changes;
  for (std::size_t k = 0; k < picked.size(); ++k) {
    for (const std::string& name : refreshed) EXPECT_TRUE(same_field(from, picked[k], into, places[k], name)) << name;
    for (const std::string& name : kept) EXPECT_TRUE(same_field(before, places[k], into, places[k], name)) << name;
  }
  for (const std::size_t untouched : {1, 2, 3})
    for (const std::string& name : refreshed) EXPECT_TRUE(same_field(before, untouched, into, untouched, name)) << name;
  // Another count than the places given is refused.
  EXPECT_THROW(unpack_particles_at(bytes, ParticleTransfer::ghost_refresh, into, std::vector<std::uint32_t>{1, 2}),
               SimulationError);
}

TEST(ParticleTransfer, AMessageThatEndsEarlyIsRefused) {
  ParticleStore from = random_store(10);
  std::vector<std::byte> bytes;
  pack_particles(from, std::vector<std::uint32_t>{1, 2, 3}, ParticleTransfer::migration, bytes);
  ParticleStore into;
  EXPECT_THROW(unpack_particles(std::span(bytes).first(bytes.size() - 1), ParticleTransfer::migration, into),
               SimulationError);
}

}  // namespace
}  // namespace regodem
