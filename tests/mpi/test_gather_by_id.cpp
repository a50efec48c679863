// The whole run's particles and sums on one rank in id order
// (src/parallel/mpi/gather_by_id.hpp), under mpirun on 1, 2 and 3 ranks: bit for bit what
// one process holds and adds, whatever the split.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "parallel/mpi/gather_by_id.hpp"
#include "parallel/mpi/particle_exchange.hpp"
#include "particle_sets.hpp"

namespace regodem {
namespace {

bool same_bytes(const auto& a, const auto& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(GatherById, TheRootHoldsEveryParticleInIdOrderBitForBit) {
  const Communicator comm;
  ParticleStore all = whole_set();
  ParticleStore mine = dealt(all, comm);
  // Split as a run would hold them: by brick, after migration.
  migrate_particles(mine, RecursiveBisection(kDomain, all.position_m, {}, comm.size()), comm);
  for (int root : {0, comm.size() - 1}) {
    ParticleStore whole = gather_particles(mine, comm, root);
    if (comm.rank() != root) {
      EXPECT_EQ(whole.size(), 0u);
      continue;
    }
    ASSERT_EQ(whole.size(), all.size());
    for (std::size_t k = 0; k < all.size(); ++k) {
      EXPECT_EQ(whole.id[k], all.id[k]);
      EXPECT_TRUE(same_bytes(whole.position_m[k], all.position_m[k]) &&
                  same_bytes(whole.velocity_m_per_s[k], all.velocity_m_per_s[k]) &&
                  same_bytes(whole.angular_velocity_rad_per_s[k], all.angular_velocity_rad_per_s[k]) &&
                  same_bytes(whole.mass_kg[k], all.mass_kg[k]) && same_bytes(whole.temperature_K[k], all.temperature_K[k]))
          << "particle " << k;
    }
  }
}

TEST(GatherById, ASumOverParticlesIsTheOneProcessSumBitForBit) {
  const Communicator comm;
  ParticleStore all = whole_set();
  // Values over 16 decades and both signs: the order of the additions shows in the bits.
  Rng rng(77);
  std::vector<double> value(all.size());
  for (double& v : value) v = (rng.uniform(0, 1) < 0.5 ? -1.0 : 1.0) * std::pow(10.0, rng.uniform(-8, 8));
  double serial = 0.0;  // one process, in id order
  for (double v : value) serial += v;
  ParticleStore mine = dealt(all, comm);
  migrate_particles(mine, RecursiveBisection(kDomain, all.position_m, {}, comm.size()), comm);
  std::vector<double> my_values(mine.size());
  for (std::size_t p = 0; p < mine.size(); ++p) my_values[p] = value[mine.id[p]];
  const double total = sum_by_id(mine.id, my_values, comm);
  EXPECT_TRUE(same_bytes(total, serial)) << total << " against " << serial;
  // The same values added in this rank's own order would not do: on more than one rank
  // the ranks' partial sums, added, differ from the serial sum in the last bits.
  if (comm.size() > 1) {
    double partial = 0.0;
    for (double v : my_values) partial += v;
    double summed = 0.0;
    MPI_Allreduce(&partial, &summed, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    EXPECT_FALSE(same_bytes(summed, serial)) << "the values do not show the order of the additions";
  }
}

}  // namespace
}  // namespace regodem
