#include "parallel/mpi/communicator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <string>

#include "core/error.hpp"

namespace regodem {

namespace {

/// Adds the wall time of its scope to a tally's seconds.
class TimedIn {
 public:
  explicit TimedIn(CommunicationTally& tally) : tally_(tally), start_s_(MPI_Wtime()) {}
  ~TimedIn() { tally_.seconds += MPI_Wtime() - start_s_; }
  TimedIn(const TimedIn&) = delete;
  TimedIn& operator=(const TimedIn&) = delete;

 private:
  CommunicationTally& tally_;
  double start_s_;
};

}  // namespace

Communicator::Communicator(MPI_Comm comm) : comm_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

std::vector<std::vector<std::byte>> Communicator::exchange(const std::vector<std::vector<std::byte>>& to_rank) const {
  const auto ranks = static_cast<std::size_t>(size_);
  if (to_rank.size() != ranks)
    throw SimulationError(fmt::format("messages for {} ranks, the run has {}", to_rank.size(), ranks));
  // MPI counts are int: a message of 2 GiB or more would need to be split.
  const auto as_count = [](std::size_t bytes) {
    if (bytes > static_cast<std::size_t>(std::numeric_limits<int>::max()))
      throw SimulationError(fmt::format("a message of {} bytes between ranks is larger than MPI's int counts", bytes));
    return static_cast<int>(bytes);
  };
  const TimedIn timed(tally_);
  std::vector<int> send_counts(ranks), send_offsets(ranks), receive_counts(ranks), receive_offsets(ranks);
  std::size_t send_total = 0;
  for (std::size_t r = 0; r < ranks; ++r) {
    send_counts[r] = r == static_cast<std::size_t>(rank_) ? 0 : as_count(to_rank[r].size());
    send_offsets[r] = as_count(send_total);
    send_total += static_cast<std::size_t>(send_counts[r]);
  }
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, comm_);
  std::size_t receive_total = 0;
  for (std::size_t r = 0; r < ranks; ++r) {
    receive_offsets[r] = as_count(receive_total);
    receive_total += static_cast<std::size_t>(receive_counts[r]);
  }
  std::vector<std::byte> send(send_total), receive(receive_total);
  for (std::size_t r = 0; r < ranks; ++r)
    if (send_counts[r] > 0)
      std::copy(to_rank[r].begin(), to_rank[r].end(), send.begin() + send_offsets[r]);
  MPI_Alltoallv(send.data(), send_counts.data(), send_offsets.data(), MPI_BYTE, receive.data(), receive_counts.data(),
                receive_offsets.data(), MPI_BYTE, comm_);
  std::vector<std::vector<std::byte>> from_rank(ranks);
  ++tally_.exchanges;
  tally_.exchange_bytes += send_total;
  for (std::size_t r = 0; r < ranks; ++r) tally_.exchange_messages += send_counts[r] > 0 ? 1 : 0;
  for (std::size_t r = 0; r < ranks; ++r)
    from_rank[r].assign(receive.begin() + receive_offsets[r],
                        receive.begin() + receive_offsets[r] + receive_counts[r]);
  return from_rank;
}

std::uint64_t Communicator::sum(std::uint64_t value) const {
  const TimedIn timed(tally_);
  ++tally_.collectives;
  std::uint64_t total = 0;
  MPI_Allreduce(&value, &total, 1, MPI_UINT64_T, MPI_SUM, comm_);
  return total;
}

std::vector<std::vector<std::byte>> Communicator::gather_to_all(const std::vector<std::byte>& mine) const {
  if (mine.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw SimulationError(fmt::format("a message of {} bytes between ranks is larger than MPI's int counts", mine.size()));
  const TimedIn timed(tally_);
  tally_.collectives += 2;
  tally_.gathered_bytes += mine.size();
  const int count = static_cast<int>(mine.size());
  const auto ranks = static_cast<std::size_t>(size_);
  std::vector<int> counts(ranks), offsets(ranks);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_);
  std::size_t total = 0;
  for (std::size_t r = 0; r < ranks; ++r) {
    if (total > static_cast<std::size_t>(std::numeric_limits<int>::max()))
      throw SimulationError(fmt::format("{} bytes gathered on every rank are more than MPI's int counts", total));
    offsets[r] = static_cast<int>(total);
    total += static_cast<std::size_t>(counts[r]);
  }
  std::vector<std::byte> all(total);
  MPI_Allgatherv(mine.data(), count, MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE, comm_);
  std::vector<std::vector<std::byte>> by_rank(ranks);
  for (std::size_t r = 0; r < ranks; ++r)
    by_rank[r].assign(all.begin() + offsets[r], all.begin() + offsets[r] + counts[r]);
  return by_rank;
}

std::uint32_t Communicator::bits_or(std::uint32_t value) const {
  const TimedIn timed(tally_);
  ++tally_.collectives;
  MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_UINT32_T, MPI_BOR, comm_);
  return value;
}

double Communicator::max(double value) const {
  const TimedIn timed(tally_);
  ++tally_.collectives;
  double largest = 0.0;
  MPI_Allreduce(&value, &largest, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return largest;
}

std::vector<double> Communicator::equal_counts_of_every_rank(std::span<const double> mine) const {
  if (mine.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw SimulationError(fmt::format("{} values for each rank are more than MPI's int counts", mine.size()));
  const TimedIn timed(tally_);
  ++tally_.collectives;
  const int count = static_cast<int>(mine.size());
  std::vector<double> values(mine.size() * static_cast<std::size_t>(size_));
  MPI_Allgather(mine.data(), count, MPI_DOUBLE, values.data(), count, MPI_DOUBLE, comm_);
  return values;
}

std::vector<std::vector<std::byte>> Communicator::gather(const std::vector<std::byte>& mine, int root) const {
  if (mine.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw SimulationError(fmt::format("a message of {} bytes between ranks is larger than MPI's int counts", mine.size()));
  const TimedIn timed(tally_);
  tally_.collectives += 2;
  tally_.gathered_bytes += mine.size();
  const int count = static_cast<int>(mine.size());
  const auto ranks = static_cast<std::size_t>(size_);
  std::vector<int> counts(rank_ == root ? ranks : 0), offsets(counts.size());
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, root, comm_);
  std::size_t total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    if (total > static_cast<std::size_t>(std::numeric_limits<int>::max()))
      throw SimulationError(fmt::format("{} bytes gathered on one rank are more than MPI's int counts", total));
    offsets[r] = static_cast<int>(total);
    total += static_cast<std::size_t>(counts[r]);
  }
  std::vector<std::byte> all(total);
  MPI_Gatherv(mine.data(), count, MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE, root, comm_);
  std::vector<std::vector<std::byte>> by_rank(counts.size());
  for (std::size_t r = 0; r < counts.size(); ++r)
    by_rank[r].assign(all.begin() + offsets[r], all.begin() + offsets[r] + counts[r]);
  return by_rank;
}

double Communicator::broadcast(double value, int root) const {
  const TimedIn timed(tally_);
  ++tally_.collectives;
  MPI_Bcast(&value, 1, MPI_DOUBLE, root, comm_);
  return value;
}

namespace {

enum ErrorKind : int { no_error = 0, input_error = 1, simulation_error = 2, other_error = 3 };

// The kind and message of an error (none: no_error).
ErrorKind describe(const std::exception_ptr& error, std::string& message) {
  if (!error) return no_error;
  try {
    std::rethrow_exception(error);
  } catch (const InputError& e) {
    message = e.what();
    return input_error;
  } catch (const SimulationError& e) {
    message = e.what();
    return simulation_error;
  } catch (const std::exception& e) {
    message = e.what();
    return other_error;
  } catch (...) {
    message = "an unknown error";
    return other_error;
  }
}

}  // namespace

void Communicator::agree(const std::exception_ptr& error) const { any_rank(false, error); }

bool Communicator::any_rank(bool mine, const std::exception_ptr& error) const {
  const TimedIn timed(tally_);
  ++tally_.collectives;
  std::string message;
  const ErrorKind kind = describe(error, message);
  // One collective for both: the lowest failing rank and, negated, the largest vote.
  int reduced[2] = {kind != no_error ? rank_ : size_, mine ? -1 : 0};
  MPI_Allreduce(MPI_IN_PLACE, reduced, 2, MPI_INT, MPI_MIN, comm_);
  const int first_failed = reduced[0];
  if (first_failed == size_) return reduced[1] < 0;
  int header[2] = {kind, static_cast<int>(message.size())};
  MPI_Bcast(header, 2, MPI_INT, first_failed, comm_);
  message.resize(static_cast<std::size_t>(header[1]));
  MPI_Bcast(message.data(), header[1], MPI_CHAR, first_failed, comm_);
  if (size_ > 1) message = fmt::format("rank {}: {}", first_failed, message);
  if (header[0] == input_error) throw InputError(message);
  if (header[0] == simulation_error) throw SimulationError(message);
  throw std::runtime_error(message);
}

void Communicator::sum_in_rank_order(std::span<double> values) const {
  if (values.size() > static_cast<std::size_t>(std::numeric_limits<int>::max() / std::max(size_, 1)))
    throw SimulationError(fmt::format("{} values to sum over {} ranks are more than MPI's int counts", values.size(),
                                      size_));
  const TimedIn timed(tally_);
  tally_.collectives += 2;
  const int count = static_cast<int>(values.size());
  std::vector<double> all(rank_ == 0 ? values.size() * static_cast<std::size_t>(size_) : 0);
  MPI_Gather(values.data(), count, MPI_DOUBLE, all.data(), count, MPI_DOUBLE, 0, comm_);
  if (rank_ == 0)
    for (std::size_t k = 0; k < values.size(); ++k) {
      double sum = 0.0;
      for (std::size_t r = 0; r < static_cast<std::size_t>(size_); ++r) sum += all[r * values.size() + k];
      values[k] = sum;
    }
  MPI_Bcast(values.data(), count, MPI_DOUBLE, 0, comm_);
}

}  // namespace regodem
