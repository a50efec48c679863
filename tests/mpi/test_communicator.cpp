// The ranks' messages and errors (src/parallel/mpi/communicator.hpp), under mpirun on 1,
// 2 and 3 ranks.
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "parallel/mpi/communicator.hpp"

namespace regodem {
namespace {

TEST(Communicator, EachRankGetsWhatEachOtherSentIt) {
  const Communicator comm;
  std::vector<std::vector<std::byte>> to_rank(static_cast<std::size_t>(comm.size()));
  // Rank s sends rank r (s + 1) * 3 + r bytes, each the value s * 16 + r.
  for (int r = 0; r < comm.size(); ++r)
    to_rank[static_cast<std::size_t>(r)].assign(static_cast<std::size_t>((comm.rank() + 1) * 3 + r),
                                                static_cast<std::byte>(comm.rank() * 16 + r));
  const std::vector<std::vector<std::byte>> got = comm.exchange(to_rank);
  ASSERT_EQ(got.size(), static_cast<std::size_t>(comm.size()));
  for (int s = 0; s < comm.size(); ++s) {
    const std::vector<std::byte>& from = got[static_cast<std::size_t>(s)];
    if (s == comm.rank()) {
      EXPECT_TRUE(from.empty());  // its own is not sent
      continue;
    }
    EXPECT_EQ(from, std::vector<std::byte>(static_cast<std::size_t>((s + 1) * 3 + comm.rank()),
                                           static_cast<std::byte>(s * 16 + comm.rank())))
        << "from rank " << s;
  }
}

TEST(Communicator, NoErrorAnywhereGoesOn) {
  const Communicator comm;
  EXPECT_NO_THROW(comm.agree(nullptr));
}

TEST(Communicator, AnErrorOnOneRankStopsEveryRankWithItsMessage) {
  const Communicator comm;
  const int failing = comm.size() - 1;
  std::exception_ptr mine;
  if (comm.rank() == failing) mine = std::make_exception_ptr(SimulationError("a grain blew up at step 7"));
  try {
    comm.agree(mine);
    FAIL() << "rank " << comm.rank() << " went on";
  } catch (const SimulationError& e) {
    const std::string expected =
        comm.size() > 1 ? "rank " + std::to_string(failing) + ": a grain blew up at step 7" : "a grain blew up at step 7";
    EXPECT_EQ(std::string(e.what()), expected);
  }
}

TEST(Communicator, TheLowestFailingRankSpeaksAndItsKindIsKept) {
  const Communicator comm;
  // Every rank but 0 fails, each with its own message; rank 1's is an input error.
  std::exception_ptr mine;
  if (comm.rank() == 1) mine = std::make_exception_ptr(InputError("bad value in the scenario"));
  if (comm.rank() > 1) mine = std::make_exception_ptr(SimulationError("rank-specific trouble"));
  if (comm.size() == 1) {
    EXPECT_NO_THROW(comm.agree(mine));
    return;
  }
  try {
    comm.agree(mine);
    FAIL() << "rank " << comm.rank() << " went on";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "rank 1: bad value in the scenario");
  }
}

}  // namespace
}  // namespace regodem
