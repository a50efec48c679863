// The particle store's field table: every per-particle array of the store is in it once
// (a field added to the class but not to the table would not be sorted, removed or
// checkpointed), with a name and a unit, and what a distributed run needs of each: the
// fields a force pass computes afresh do not migrate, and ghosts get what a contact reads.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "core/particle_store.hpp"

namespace regodem {
namespace {

TEST(ParticleStoreFields, EveryArrayIsInTheTableOnceWithANameAndAUnit) {
  ParticleStore store;
  std::size_t fields = 0;
  std::set<std::string> names;
  std::set<const void*> arrays;
  store.for_each_described_field([&](const ParticleField& field, auto& array) {
    ++fields;
    EXPECT_TRUE(names.insert(field.name).second) << field.name;
    EXPECT_TRUE(arrays.insert(&array).second) << field.name;
    EXPECT_FALSE(std::string(field.unit).empty()) << field.name;
  });
  // The store holds its arrays (all std::vector, of one size whatever the element) and
  // the next id: any other array in the class is one the table does not list.
  EXPECT_EQ(sizeof(ParticleStore), fields * sizeof(std::vector<double>) + sizeof(std::uint64_t));
  EXPECT_EQ(fields, 17u);
}

TEST(ParticleStoreFields, AddAppendsToEveryField) {
  ParticleStore store;
  NewParticle p;
  p.radius_m = 1e-3;
  p.density_kg_per_m3 = 3000.0;
  store.add(p);
  store.add(p);
  store.for_each_described_field([&](const ParticleField& field, auto& array) {
    EXPECT_EQ(array.size(), 2u) << field.name;
  });
}

TEST(ParticleStoreFields, WhatMigratesAndWhatGhostsNeed) {
  ParticleStore store;
  std::set<std::string> migrates, ghosts;
  store.for_each_described_field([&](const ParticleField& field, auto&) {
    if (field.migrates) migrates.insert(field.name);
    if (field.ghosts_need) ghosts.insert(field.name);
    EXPECT_TRUE(field.migrates || !field.ghosts_need) << field.name;  // a ghost's fields are a particle's
  });
  for (const char* computed : {"torque", "heat_flow"}) EXPECT_FALSE(migrates.count(computed)) << computed;
  // The force travels and goes to the ghosts: a neighbour build reads it (each particle's
  // half of the skin), the same on every rank that holds the particle.
  for (const char* read_by_contacts : {"id", "radius", "inverse_mass", "inverse_inertia", "position", "velocity",
                                       "angular_velocity", "material", "temperature", "conductivity", "force"})
    EXPECT_TRUE(ghosts.count(read_by_contacts)) << read_by_contacts;
}

}  // namespace
}  // namespace regodem
