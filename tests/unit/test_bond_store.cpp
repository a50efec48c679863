// The bond store's operations that treat every per-bond field alike (its field table,
// BondStore::for_each_field): a removal of broken bonds moves every field of each kept
// bond with it, in order, and refreshes each particle's bond index; a bond packed for
// another rank arrives with every field that travels, in a layout of fixed order, its
// local indices to be found again and its pass results zero.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "contact/bond_store.hpp"
#include "parallel/bond_transfer.hpp"

namespace regodem {
namespace {

ParticleStore particles_in_a_row(std::size_t n) {
  ParticleStore store;
  for (std::size_t i = 0; i < n; ++i) {
    NewParticle p;
    p.radius_m = 1e-3;
    p.density_kg_per_m3 = 3000.0;
    p.position_m = {2e-3 * static_cast<double>(i), 0.0, 0.0};
    store.add(p);
  }
  return store;
}

/// Bonds between neighbours in the row, bond b with values that name it in every field.
BondStore named_bonds(const ParticleStore& particles, std::size_t count) {
  BondStore bonds;
  for (std::size_t b = 0; b < count; ++b) {
    const auto a = static_cast<std::uint32_t>(b), c = static_cast<std::uint32_t>(b + 1);
    const double name = static_cast<double>(b);
    bonds.add(particles, a, c, static_cast<std::uint16_t>(b % 3), BondSection::of_radius(1e-4 * (1.0 + name)));
    bonds.rest_length_m[b] = 1e-3 * (1.0 + name);
    bonds.sequence[b] = static_cast<std::uint32_t>(100 + b);
    for (int row = 0; row < BondStore::state_rows; ++row) bonds.state[row][b] = 1000.0 * name + row;
    bonds.action[b].force_on_i_N = {name, 0.0, 0.0};
    bonds.action[b].loss_W = 0.5 * name;
    bonds.heat_to_i_W[b] = 2.0 * name;
  }
  return bonds;
}

/// Checks that bond k of `bonds` holds what named_bonds gave bond b of the row.
void expect_bond(const BondStore& bonds, std::size_t k, std::size_t b, bool with_pass_results) {
  const double name = static_cast<double>(b);
  EXPECT_EQ(bonds.id_j[k] - bonds.id_i[k], 1u) << k;
  EXPECT_EQ(bonds.kind[k], b % 3) << k;
  EXPECT_EQ(bonds.rest_length_m[k], 1e-3 * (1.0 + name)) << k;
  EXPECT_EQ(bonds.section[k].radius_m, 1e-4 * (1.0 + name)) << k;
  EXPECT_EQ(bonds.sequence[k], 100 + b) << k;
  for (int row = 0; row < BondStore::state_rows; ++row) EXPECT_EQ(bonds.state[row][k], 1000.0 * name + row) << k;
  EXPECT_EQ(bonds.action[k].force_on_i_N.x, with_pass_results ? name : 0.0) << k;
  EXPECT_EQ(bonds.action[k].loss_W, with_pass_results ? 0.5 * name : 0.0) << k;
  EXPECT_EQ(bonds.heat_to_i_W[k], with_pass_results ? 2.0 * name : 0.0) << k;
  EXPECT_EQ(bonds.broken[k], 0) << k;
}

TEST(BondStore, EveryFieldOfTheTableHasOneValuePerBond) {
  const ParticleStore particles = particles_in_a_row(10);
  BondStore bonds = named_bonds(particles, 9);
  // (The count of the table's fields is a static_assert in bond_store.hpp.)
  int field = 0;
  BondStore::for_each_field([&](auto member, auto) {
    EXPECT_EQ((bonds.*member).size(), bonds.size()) << "field " << field;
    ++field;
  });
}

TEST(BondStore, ARemovalMovesEveryFieldOfTheKeptBondsInOrder) {
  const ParticleStore particles = particles_in_a_row(7000);  // past the threads' threshold
  BondStore bonds = named_bonds(particles, 6999);
  std::vector<std::size_t> kept;
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    bonds.broken[b] = b % 7 == 3 || b % 11 == 0;
    if (!bonds.broken[b]) kept.push_back(b);
  }
  bonds.remove_broken(particles, 2);
  ASSERT_EQ(bonds.size(), kept.size());
  for (std::size_t k = 0; k < kept.size(); ++k) {
    expect_bond(bonds, k, kept[k], true);
    EXPECT_EQ(bonds.id_i[k], particles.id[kept[k]]) << k;
    EXPECT_EQ(bonds.local_i[k], kept[k]) << k;
    EXPECT_EQ(bonds.local_j[k], kept[k] + 1) << k;
  }
  BondStore::for_each_field([&](auto member, auto) { EXPECT_EQ((bonds.*member).size(), kept.size()); });
  EXPECT_EQ(bonds.broken.size(), kept.size());
  // Each particle's entries name its bonds that remain, in bond order.
  for (std::size_t p = 0; p < particles.size(); ++p)
    for (std::uint32_t e = bonds.bond_offset[p]; e < bonds.bond_offset[p + 1]; ++e) {
      const std::uint32_t b = bonds.bond_entry[e] >> 1;
      EXPECT_EQ((bonds.bond_entry[e] & 1u) ? bonds.local_j[b] : bonds.local_i[b], p);
      if (e > bonds.bond_offset[p]) {
        EXPECT_LT(bonds.bond_entry[e - 1] >> 1, b);
      }
    }
  EXPECT_EQ(bonds.bond_offset.back(), 2 * kept.size());
}

TEST(BondStore, ABondSentToAnotherRankArrivesWithWhatTravels) {
  const ParticleStore particles = particles_in_a_row(20);
  const BondStore sent = named_bonds(particles, 19);
  const std::vector<std::uint32_t> which{4, 0, 17};
  std::vector<std::byte> bytes;
  pack_bonds(sent, which, bytes);
  BondStore arrived;
  unpack_bonds(bytes, arrived);  // its layout: ABondsBytesKeepTheirLayout
  ASSERT_EQ(arrived.size(), which.size());
  for (std::size_t k = 0; k < which.size(); ++k) {
    expect_bond(arrived, k, which[k], false);
    EXPECT_EQ(arrived.id_i[k], sent.id_i[which[k]]);
    EXPECT_EQ(arrived.local_i[k], 0xFFFFFFFFu);  // found again by refresh_indices
    EXPECT_EQ(arrived.local_j[k], 0xFFFFFFFFu);
  }
  ASSERT_EQ(arrived.refresh_indices(particles), arrived.size());
  for (std::size_t k = 0; k < which.size(); ++k) {
    EXPECT_EQ(arrived.local_i[k], which[k]);
    EXPECT_EQ(arrived.local_j[k], which[k] + 1);
  }
}

// The bytes of one bond, field by field in their order (what ranks of one build exchange):
// the two ids, the kind, the rest length, the section, the sequence, then the 11 state rows.
TEST(BondStore, ABondsBytesKeepTheirLayout) {
  const ParticleStore particles = particles_in_a_row(20);
  const BondStore sent = named_bonds(particles, 19);
  const std::vector<std::uint32_t> which{5};
  std::vector<std::byte> bytes;
  pack_bonds(sent, which, bytes);
  std::size_t at = sizeof(std::uint64_t);  // the count
  const auto next = [&](auto& value) {
    ASSERT_LE(at + sizeof value, bytes.size());
    std::memcpy(&value, bytes.data() + at, sizeof value);
    at += sizeof value;
  };
  ParticleId id_i = 0, id_j = 0;
  std::uint16_t kind = 0;
  double rest_length_m = 0.0;
  BondSection section;
  std::uint32_t sequence = 0;
  next(id_i);
  next(id_j);
  next(kind);
  next(rest_length_m);
  next(section);
  next(sequence);
  EXPECT_EQ(id_i, sent.id_i[5]);
  EXPECT_EQ(id_j, sent.id_j[5]);
  EXPECT_EQ(kind, sent.kind[5]);
  EXPECT_EQ(rest_length_m, sent.rest_length_m[5]);
  EXPECT_EQ(section.radius_m, sent.section[5].radius_m);
  EXPECT_EQ(sequence, sent.sequence[5]);
  for (int row = 0; row < BondStore::state_rows; ++row) {
    double value = 0.0;
    next(value);
    EXPECT_EQ(value, sent.state[row][5]) << row;
  }
  EXPECT_EQ(at, bytes.size());
  EXPECT_EQ(bytes_per_bond(), at - sizeof(std::uint64_t));
}

}  // namespace
}  // namespace regodem
