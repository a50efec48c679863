// The default thread count leaves out the cores other runnable processes hold (two
// threads on a half-busy 2-core machine ran the heated 20,000 bed at 3.6e6
// particle-steps/s against 6.4e6 on one), and says so.
#include <gtest/gtest.h>

#include "core/thread_choice.hpp"

namespace regodem {
namespace {

TEST(ThreadChoice, AnIdleMachineUsesEveryThread) {
  const ThreadChoice choice = choose_threads(2, 0);
  EXPECT_EQ(choice.threads, 2);
  EXPECT_TRUE(choice.note.empty());
}

TEST(ThreadChoice, BusyCoresAreLeftOutAndTheNoteSaysWhy) {
  const ThreadChoice choice = choose_threads(2, 1);
  EXPECT_EQ(choice.threads, 1);
  EXPECT_NE(choice.note.find("1 other runnable process on 2 threads): running on 1 thread"), std::string::npos)
      << choice.note;
  EXPECT_EQ(choose_threads(16, 5).threads, 11);
  EXPECT_EQ(choose_threads(2, 7).threads, 1);  // never fewer than one
}

TEST(ThreadChoice, ThisMachinesReadingIsACount) { EXPECT_GE(runnable_processes_elsewhere(), 0); }

}  // namespace
}  // namespace regodem
