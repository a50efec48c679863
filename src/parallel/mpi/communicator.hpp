#pragma once
// The ranks of a run over MPI (issue 19), as the rest of the code needs them: who am I,
// how many are we, and messages of bytes to every other rank at once. Only this folder
// includes mpi.h, and only the `regodem_mpi` library is built from it (where CMake finds
// MPI), so the engine builds and runs without MPI.
#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <exception>
#include <span>
#include <vector>

namespace regodem {

/// What a rank has sent since its Communicator was made: the counts a cost model of a run
/// over many ranks needs (src/parallel/rank_cost_model.hpp), measured rather than assumed.
struct CommunicationTally {
  std::uint64_t collectives = 0;        // latency-bound rounds among all ranks (an allreduce, a broadcast, ...)
  std::uint64_t exchanges = 0;          // exchange(): an all-to-all of counts, then the messages
  std::uint64_t exchange_messages = 0;  // of which messages with bytes in them, sent by this rank
  std::uint64_t exchange_bytes = 0;     // and their bytes
  std::uint64_t gathered_bytes = 0;     // this rank's bytes handed to gather / gather_to_all
  double seconds = 0.0;                 // wall time inside the calls above (waiting for other ranks included)
};

class Communicator {
 public:
  explicit Communicator(MPI_Comm comm = MPI_COMM_WORLD);
  int rank() const { return rank_; }
  int size() const { return size_; }
  /// Sends to_rank[r] to each rank r (to_rank has size() entries; this rank's own is
  /// not sent) and returns what each rank sent to this one, by rank.
  std::vector<std::vector<std::byte>> exchange(const std::vector<std::vector<std::byte>>& to_rank) const;
  /// The sum over the ranks.
  std::uint64_t sum(std::uint64_t value) const;
  /// The largest over the ranks.
  double max(double value) const;
  /// Every rank's values on every rank, by rank, one after the other (one collective).
  /// Every rank must give as many (HaloExchange::values_of_every_rank takes any count, in
  /// two collectives).
  std::vector<double> equal_counts_of_every_rank(std::span<const double> mine) const;
  /// The bitwise or over the ranks.
  std::uint32_t bits_or(std::uint32_t value) const;
  /// Every rank's bytes on rank `root`, by rank (the other ranks get nothing).
  std::vector<std::vector<std::byte>> gather(const std::vector<std::byte>& mine, int root) const;
  /// Every rank's bytes on every rank, by rank.
  std::vector<std::vector<std::byte>> gather_to_all(const std::vector<std::byte>& mine) const;
  /// Root's value on every rank.
  double broadcast(double value, int root) const;
  /// Replaces each value by its sum over the ranks, added in rank order on rank 0 and sent
  /// to all: the same bits on every rank, and on every run with this many ranks.
  void sum_in_rank_order(std::span<double> values) const;
  /// A point every rank reaches with the error it met since the last one (or none).
  /// When any rank brings one, every rank throws the error of the lowest such rank, its
  /// kind kept (InputError, SimulationError, else std::runtime_error) and its message
  /// prefixed by "rank R: " on more than one rank: all ranks stop with the message of
  /// the rank that failed, and none waits for a rank that has stopped.
  void agree(const std::exception_ptr& error) const;
  /// Whether any rank's `mine` is true, and agree(error), in one collective.
  bool any_rank(bool mine, const std::exception_ptr& error) const;

  /// What this rank has sent through this communicator so far.
  const CommunicationTally& tally() const { return tally_; }

 private:
  MPI_Comm comm_;
  mutable CommunicationTally tally_;
  int rank_ = 0, size_ = 1;
};

}  // namespace regodem
