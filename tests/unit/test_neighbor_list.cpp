// Neighbour lists: the half list holds exactly the pairs within R_i + R_j + skin (each
// once) for a 4:1 size mixture, also when fast particles have their own, larger share
// of the skin (NeighborSkin), and the contact history follows the particle ids
// through a rebuild that reorders the particles.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <utility>

#include "contact/neighbor_list.hpp"
#include "core/rng.hpp"

namespace regodem {
namespace {

ParticleStore random_mixture(std::size_t n, std::uint64_t seed) {
  ParticleStore store;
  Rng rng(seed);
  for (std::size_t i = 0; i < n; ++i) {
    NewParticle p;
    p.radius_m = i % 10 == 0 ? 1.2e-3 : 0.3e-3;  // 0.6 and 2.4 mm diameters
    p.density_kg_per_m3 = 3000.0;
    p.position_m = {rng.uniform(0.0, 0.01), rng.uniform(0.0, 0.01), rng.uniform(0.0, 0.01)};
    store.add(p);
  }
  return store;
}

using IdPair = std::pair<ParticleId, ParticleId>;

IdPair ordered(ParticleId a, ParticleId b) { return {std::min(a, b), std::max(a, b)}; }

/// Every pair of the list by ids (a pair listed twice is there twice); each must be
/// listed by its owner.
std::multiset<IdPair> listed_pairs(const ParticleStore& store, const NeighborList& list) {
  std::multiset<IdPair> found;
  for (std::size_t i = 0; i < store.size(); ++i)
    for (std::uint32_t k = list.offset[i]; k < list.offset[i + 1]; ++k) {
      const std::uint32_t j = list.partner[k];
      EXPECT_TRUE(owns_pair(store.radius_m[i], store.id[i], store.radius_m[j], store.id[j]));
      found.insert(ordered(store.id[i], store.id[j]));
    }
  return found;
}

TEST(NeighborList, HalfListHoldsExactlyThePairsWithinTheCutoff) {
  ParticleStore store = random_mixture(1500, 5);
  const double skin = 0.06e-3;
  NeighborList list;
  const CellGrid grid({0, 0, 0}, {0.01, 0.01, 0.01}, 0.6e-3 + skin, 1e6);
  list.rebuild(store, WallSet{}, grid, skin, 2);

  std::set<IdPair> expected;
  for (std::size_t i = 0; i < store.size(); ++i)
    for (std::size_t j = i + 1; j < store.size(); ++j) {
      const double cutoff = store.radius_m[i] + store.radius_m[j] + skin;
      if (norm2(store.position_m[i] - store.position_m[j]) < cutoff * cutoff)
        expected.insert(ordered(store.id[i], store.id[j]));
    }
  const std::multiset<IdPair> found = listed_pairs(store, list);
  ASSERT_GT(expected.size(), 100u);
  EXPECT_EQ(found.size(), expected.size());  // no pair twice
  EXPECT_EQ(std::set<IdPair>(found.begin(), found.end()), expected);
}

// Under MPI (issue 19) the build is told which particles are ghosts: it lists every pair
// with at least one own particle, exactly as without flags, no pair of two ghosts, and no
// wall for a ghost; the flags follow the sort. Every third particle is a ghost, and a
// wall plane crosses the box, so both kinds of entry would be there without the flags.
TEST(NeighborList, GhostsAreListedOnlyWithOwnParticles) {
  ParticleStore plain = random_mixture(1500, 11);
  const double skin = 0.06e-3;
  WallSet walls;
  walls.add_plane(walls.add_body("floor", {}), {0, 0, 5e-3}, {0, 0, 1}, 0);
  const CellGrid grid({0, 0, 0}, {0.01, 0.01, 0.01}, 0.6e-3 + skin, 1e6);
  ParticleStore flagged = plain;
  std::vector<std::uint8_t> ghost(flagged.size());
  for (std::size_t i = 0; i < ghost.size(); ++i) ghost[i] = i % 3 == 0;
  NeighborList all, own;
  all.rebuild(plain, walls, grid, skin, 2);
  own.rebuild(flagged, walls, grid, skin, 2, false, &ghost);

  ASSERT_EQ(flagged.id, plain.id);  // the same sort
  for (std::size_t i = 0; i < ghost.size(); ++i) ASSERT_EQ(ghost[i], flagged.id[i] % 3 == 0) << i;
  std::multiset<IdPair> expected;
  std::size_t ghost_pairs = 0, ghost_walls = 0;
  for (std::size_t i = 0; i < plain.size(); ++i) {
    for (std::uint32_t k = all.offset[i]; k < all.offset[i + 1]; ++k) {
      const std::uint32_t j = all.partner[k];
      if (ghost[i] && ghost[j]) ++ghost_pairs;
      else expected.insert(ordered(plain.id[i], plain.id[j]));
    }
    if (ghost[i]) {
      ghost_walls += all.wall_offset[i + 1] - all.wall_offset[i];
      EXPECT_EQ(own.wall_offset[i + 1], own.wall_offset[i]) << i;
    } else {
      EXPECT_EQ(own.wall_offset[i + 1] - own.wall_offset[i], all.wall_offset[i + 1] - all.wall_offset[i]) << i;
    }
  }
  ASSERT_GT(ghost_pairs, 100u);
  ASSERT_GT(ghost_walls, 10u);
  EXPECT_EQ(listed_pairs(flagged, own), expected);
}

// NeighborSkin: a particle's half is clamp(8 |v| dt, skin/2, 4 skin/2); a pair is listed
// within R_i + R_j + h_i + h_j. Every tenth particle is fast (up to 8x the speed at which
// 8 steps cover the slow half), so the fast ones' own search finds pairs of every kind:
// fast-slow both ways round and fast-fast.
TEST(NeighborList, FastParticlesReachAsFarAsTheirOwnHalfOfTheSkin) {
  ParticleStore store = random_mixture(1500, 7);
  const double skin = 0.06e-3, dt = 1e-6;
  Rng rng(3);
  for (std::size_t i = 0; i < store.size(); ++i)
    if (i % 10 == 3) store.velocity_m_per_s[i] = {rng.uniform(-1, 1) * 8.0 * (0.5 * skin) / (8.0 * dt), 0.0, 0.0};
  NeighborSkin policy(skin);
  policy.time_step_s = dt;
  policy.steps_ahead = 8.0;
  policy.max_half_skin_factor = 4.0;
  NeighborList list;
  const CellGrid grid({0, 0, 0}, {0.01, 0.01, 0.01}, 0.6e-3 + skin, 1e6);
  list.rebuild(store, WallSet{}, grid, policy, 2);

  const auto half = [&](std::size_t i) {
    return std::clamp(8.0 * norm(store.velocity_m_per_s[i]) * dt, 0.5 * skin, 2.0 * skin);
  };
  std::set<IdPair> expected;
  std::size_t fast_pairs = 0;
  for (std::size_t i = 0; i < store.size(); ++i) {
    EXPECT_DOUBLE_EQ(list.inverse_half_skin2()[i], 1.0 / (half(i) * half(i))) << i;
    for (std::size_t j = i + 1; j < store.size(); ++j) {
      const double cutoff = store.radius_m[i] + store.radius_m[j] + half(i) + half(j);
      if (norm2(store.position_m[i] - store.position_m[j]) < cutoff * cutoff) {
        expected.insert(ordered(store.id[i], store.id[j]));
        if (half(i) > 0.5 * skin || half(j) > 0.5 * skin) ++fast_pairs;
      }
    }
  }
  const std::multiset<IdPair> found = listed_pairs(store, list);
  ASSERT_GT(fast_pairs, 50u);
  EXPECT_EQ(found.size(), expected.size());  // no pair twice
  EXPECT_EQ(std::set<IdPair>(found.begin(), found.end()), expected);

  // The lists hold until a particle has moved more than its own half.
  const auto moved_ratio2 = [&](std::size_t i, double distance_m) { return distance_m * distance_m / (half(i) * half(i)); };
  std::size_t fast = 0;
  while (half(fast) <= 0.5 * skin) ++fast;
  EXPECT_FALSE(list.needs_rebuild(store.size(), moved_ratio2(fast, 0.99 * half(fast)), WallSet{}));
  EXPECT_TRUE(list.needs_rebuild(store.size(), moved_ratio2(fast, 1.01 * half(fast)), WallSet{}));
}

TEST(NeighborList, HistoryFollowsIdsThroughAReorderingRebuild) {
  ParticleStore store = random_mixture(800, 9);
  const double skin = 0.1e-3;
  const CellGrid grid({0, 0, 0}, {0.01, 0.01, 0.01}, 0.6e-3 + skin, 1e6);
  NeighborList list;
  list.rebuild(store, WallSet{}, grid, skin, 1);
  // A history value that encodes the id pair it belongs to.
  auto mark = [](ParticleId a, ParticleId b) { return Vec3{double(a), double(b), 1.0}; };
  std::map<IdPair, Vec3> written;
  for (std::size_t i = 0; i < store.size(); ++i)
    for (std::uint32_t k = list.offset[i]; k < list.offset[i + 1]; ++k) {
      const ParticleId a = store.id[i], b = store.id[list.partner[k]];
      list.tangential_history_m[k] = mark(a, b);
      written[{a, b}] = mark(a, b);
    }
  // Mirror the packing (x -> L - x for every coordinate): every distance, and so every
  // pair, stays; the cell order reverses, so the rebuild reorders the particles, and
  // it runs on two threads.
  for (Vec3& x : store.position_m) x = Vec3{0.01, 0.01, 0.01} - x;
  const std::vector<ParticleId> order_before = store.id;
  list.rebuild(store, WallSet{}, grid, skin, 2);
  ASSERT_NE(store.id, order_before);
  std::size_t checked = 0;
  for (std::size_t i = 0; i < store.size(); ++i)
    for (std::uint32_t k = list.offset[i]; k < list.offset[i + 1]; ++k) {
      const ParticleId a = store.id[i], b = store.id[list.partner[k]];
      ASSERT_TRUE(written.count({a, b}));
      EXPECT_EQ(list.tangential_history_m[k], (written[{a, b}]));
      ++checked;
    }
  EXPECT_EQ(checked, written.size());
}


/// Pairs in the list after one build of the given particles and walls.
std::size_t pairs_listed(const std::vector<std::pair<Vec3, double>>& spheres, const WallSet& walls) {
  ParticleStore store;
  for (const auto& [x, r] : spheres) {
    NewParticle p;
    p.position_m = x;
    p.radius_m = r;
    p.density_kg_per_m3 = 3000.0;
    store.add(p);
  }
  NeighborList list;
  const CellGrid grid({-0.02, -0.02, -0.02}, {0.02, 0.02, 0.02}, 0.7e-3, 1e6);
  list.rebuild(store, walls, grid, 0.05e-3, 1);
  return list.pair_count();
}

// Two particles pressed against a thin wall from opposite sides overlap each other
// through it: the pair is left out, or they would push and conduct through the wall.
// Beside a disk's rim, where nothing lies between them, they stay a pair.
TEST(NeighborList, PairsAcrossADiskOrASieveShellAreLeftOut) {
  const double r = 0.3e-3, big = 1.2e-3, overlap = 1e-6;
  WallSet disk;
  disk.add_disk(disk.add_body("sieve", {}), {0, 0, 0}, {0, 0, 1}, 5e-3, 0);
  EXPECT_EQ(pairs_listed({{{0, 0, r - overlap}, r}, {{1e-5, 0, -(r - overlap)}, r}}, disk), 0u);
  EXPECT_EQ(pairs_listed({{{0, 0, big - overlap}, big}, {{0, 0, -(r - overlap)}, r}}, disk), 0u);
  EXPECT_EQ(pairs_listed({{{6e-3, 0, r - overlap}, r}, {{6e-3, 0, -(r - overlap)}, r}}, disk), 1u);
  EXPECT_EQ(pairs_listed({{{0, 0, r - overlap}, r}, {{0, 0, -(r - overlap)}, r}}, WallSet{}), 1u);

  // A sieve segment: shell of radius 11 mm, a fine particle inside, a coarse one outside.
  WallSet sieve;
  sieve.add_sieve_segment(sieve.add_body("sieve[1]", {}), {0, 0, -6e-3}, {0, 0, 1}, 11e-3, 12e-3, true, true,
                          false, 0);
  EXPECT_EQ(pairs_listed({{{11e-3 - r + overlap, 0, 0}, r}, {{11e-3 + big - overlap, 0, 0}, big}}, sieve), 0u);
  // Side by side inside the shell they touch as usual.
  EXPECT_EQ(pairs_listed({{{11e-3 - r + overlap, 0, 0}, r}, {{11e-3 - r + overlap, 2 * r - overlap, 0}, r}}, sieve),
            1u);
}

}  // namespace
}  // namespace regodem
