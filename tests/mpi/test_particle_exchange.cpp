// Particles between ranks (src/parallel/mpi/particle_exchange.hpp), run by CTest with
// mpirun on 1, 2 and 3 ranks. Every rank draws the same particles from one seed, so each
// can check what it holds against the whole set: after migration, exactly the particles
// in its brick, every migrating field bit for bit; its ghosts, every other rank's particle
// that can pair with one of its own (brute force over all pairs), none beyond the brick's
// farthest reach.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <map>

#include "parallel/mpi/particle_exchange.hpp"
#include "particle_sets.hpp"

namespace regodem {
namespace {

RecursiveBisection bricks_of(ParticleStore& all, int ranks) {
  return RecursiveBisection(kDomain, all.position_m, {}, ranks);
}

bool same_bytes(const auto& a, const auto& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(ParticleExchange, MigrationLeavesEachRankExactlyTheParticlesOfItsBrick) {
  const Communicator comm;
  ParticleStore all = whole_set();
  const RecursiveBisection bricks = bricks_of(all, comm.size());
  ParticleStore mine = dealt(all, comm);
  const std::size_t left = migrate_particles(mine, bricks, comm);
  EXPECT_EQ(comm.sum(mine.size()), kParticles);
  if (comm.size() == 1) {
    EXPECT_EQ(left, 0u);
  }
  std::size_t expected = 0;
  for (std::size_t k = 0; k < all.size(); ++k) expected += bricks.rank_of(all.position_m[k]) == comm.rank();
  EXPECT_EQ(mine.size(), expected);
  for (std::size_t p = 0; p < mine.size(); ++p) {
    const std::size_t k = mine.id[p];
    ASSERT_LT(k, all.size());
    EXPECT_EQ(bricks.rank_of(mine.position_m[p]), comm.rank());
    EXPECT_TRUE(same_bytes(mine.position_m[p], all.position_m[k]) &&
                same_bytes(mine.velocity_m_per_s[p], all.velocity_m_per_s[k]) &&
                same_bytes(mine.angular_velocity_rad_per_s[p], all.angular_velocity_rad_per_s[k]) &&
                same_bytes(mine.radius_m[p], all.radius_m[k]) && same_bytes(mine.mass_kg[p], all.mass_kg[k]) &&
                same_bytes(mine.inv_inertia[p], all.inv_inertia[k]) &&
                same_bytes(mine.temperature_K[p], all.temperature_K[k]) && mine.material[p] == all.material[k] &&
                mine.region[p] == all.region[k])
        << "particle " << k;
  }
  // The particles move (each by its velocity over 10 ms): those that crossed a face go
  // on to their new brick, and still none is lost or doubled.
  for (std::size_t p = 0; p < mine.size(); ++p) mine.position_m[p] += mine.velocity_m_per_s[p] * 0.01;
  migrate_particles(mine, bricks, comm);
  EXPECT_EQ(comm.sum(mine.size()), kParticles);
  for (std::size_t p = 0; p < mine.size(); ++p) EXPECT_EQ(bricks.rank_of(mine.position_m[p]), comm.rank());
}

TEST(ParticleExchange, GhostsAreTheOtherRanksParticlesWithinReach) {
  const Communicator comm;
  ParticleStore all = whole_set();
  const RecursiveBisection bricks = bricks_of(all, comm.size());
  ParticleStore mine = dealt(all, comm);
  migrate_particles(mine, bricks, comm);
  // The set's grains are about 8 mm apart: a skin of 5 mm makes dozens of pairs across
  // each rank's faces (41-94 grains of other ranks per rank on 2 and 3 ranks), so that the
  // check below checks something.
  const double skin = 5e-3;
  ParticleStore ghosts;
  exchange_ghosts(mine, bricks, skin, comm, ghosts);
  // Brute force over every pair: each particle of another brick that one of this brick's
  // can be listed with (within their two radii and the skin) is a ghost, none missed.
  std::vector<std::size_t> here;
  double largest_here = 0.0;
  for (std::size_t k = 0; k < all.size(); ++k)
    if (bricks.rank_of(all.position_m[k]) == comm.rank()) {
      here.push_back(k);
      largest_here = std::max(largest_here, all.radius_m[k]);
    }
  std::vector<ParticleId> needed, got(ghosts.id);
  for (std::size_t k = 0; k < all.size(); ++k) {
    if (bricks.rank_of(all.position_m[k]) == comm.rank()) continue;
    for (const std::size_t o : here)
      if (norm(all.position_m[k] - all.position_m[o]) <= all.radius_m[k] + all.radius_m[o] + skin) {
        needed.push_back(all.id[k]);
        break;
      }
  }
  std::sort(got.begin(), got.end());
  EXPECT_TRUE(std::includes(got.begin(), got.end(), needed.begin(), needed.end()))
      << needed.size() << " particles can pair with this brick's, " << got.size() << " ghosts";
  // And none is farther from the brick than its radius, the brick's largest and the skin.
  for (std::size_t g = 0; g < ghosts.size(); ++g)
    EXPECT_LE(bricks.brick(comm.rank()).distance_m(ghosts.position_m[g]), ghosts.radius_m[g] + largest_here + skin)
        << "ghost " << ghosts.id[g];
  if (comm.size() > 1) {
    EXPECT_GT(needed.size(), 20u);
  }
  for (std::size_t g = 0; g < ghosts.size(); ++g) {
    const std::size_t k = ghosts.id[g];
    EXPECT_TRUE(same_bytes(ghosts.position_m[g], all.position_m[k]) &&
                same_bytes(ghosts.velocity_m_per_s[g], all.velocity_m_per_s[k]) &&
                same_bytes(ghosts.radius_m[g], all.radius_m[k]) &&
                same_bytes(ghosts.temperature_K[g], all.temperature_K[k]))
        << "ghost " << k;
  }
}

}  // namespace
}  // namespace regodem
