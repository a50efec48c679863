// `regodem run`: read and build the scenario, prepare the output directory, run every
// stage with progress on stderr, write summary.json, and end with one line that says
// how it went and where the outputs are (the run itself: run_session.cpp).
#include <omp.h>

#include <csignal>
#include <cstdio>
#include <exception>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "commands.hpp"
#include "core/error.hpp"
#include "run_ranks.hpp"
#include "run_session.hpp"
#include "signal_handling.hpp"

namespace regodem::app {
namespace {

std::string signal_name(int signal_number) {
  if (signal_number == SIGINT) return "SIGINT";
  if (signal_number == SIGTERM) return "SIGTERM";
  return fmt::format("signal {}", signal_number);
}

/// `regodem run`, or with `resume` the continuation of a run from its checkpoint.
int execute(const RunOptions& requested, const ResumePoint* resume) {
  // First of all, so that a signal while the scenario is read or built still ends in a
  // summary and a checkpoint (at the run's first step boundary).
  const std::atomic<bool>& stop_requested = install_stop_request_handlers();
  const ThreadChoice choice = choose_run_threads(requested.threads);
  if (!choice.note.empty() && launcher_rank() == 0) fmt::print(stderr, "regodem: note: {}\n", choice.note);
  omp_set_num_threads(choice.threads);
  RunOptions options = requested;
  options.threads = choice.threads;

  // Under mpirun every rank runs the same plan over its brick; rank 0 writes.
  std::optional<RunRanks> ranks;
  std::unique_ptr<RunSession> session;
  try {
    if (started_as_mpi_rank()) {
      ranks.emplace();
      options.mpi_ranks = ranks->size();
    }
    const bool writer = !ranks || ranks->rank() == 0;
    // Under MPI a setup error of any rank stops every rank, with the first one's message:
    // once the scenario is built (before rank 0 clears the directory) and once begun.
    const auto every_rank_agrees = [&](const std::exception_ptr& failed) {
      if (!ranks) {
        if (failed) std::rethrow_exception(failed);
        return true;
      }
      try {
        ranks->agree(failed);
        return true;
      } catch (const std::exception& error) {
        if (session) session->abandon();
        if (writer) fmt::print(stderr, "regodem: error: {}\n", error.what());
        return false;
      }
    };
    std::exception_ptr failed;
    try {
      session = std::make_unique<RunSession>(options, resume, std::nullopt, writer);
      if (ranks) ranks->take(session->prepared().simulation());
    } catch (const std::exception&) {
      if (!ranks) throw;
      failed = std::current_exception();
    }
    if (!every_rank_agrees(failed)) return exit_status::bad_input;
    // A signal while the scenario was read or built: stop before any old output goes.
    if (stop_requested.load() && !ranks) {
      session->abandon();
      fmt::print(stderr, "regodem: interrupted by {} before the run started; nothing in '{}' was changed\n",
                 signal_name(stop_signal()), session->directory().string());
      return exit_status::interrupted;
    }
    try {
      session->begin(writer ? stderr : nullptr);
    } catch (const std::exception&) {
      if (!ranks) throw;
      failed = std::current_exception();
    }
    if (!every_rank_agrees(failed)) return exit_status::bad_input;
    if (ranks && writer && ranks->size() > 1)
      fmt::print(stderr, "regodem: over {} MPI ranks (rank 0 writes the outputs)\n", ranks->size());
  } catch (const InputError& error) {
    fmt::print(stderr, "regodem: error: {}\n", error.what());
    return exit_status::bad_input;
  }
  const bool writer = !ranks || ranks->rank() == 0;
  const RunEnding ending = session->run(stop_requested);
  if (writer && ending.status == RunStatus::failed && !ending.outcome.message.empty())
    fmt::print(stderr, "regodem: {}\n", ending.outcome.message);
  std::string last_line;
  try {
    last_line = session->finish(ending, signal_name(stop_signal()));
  } catch (const std::exception& error) {
    // Rank 0 could not write the summary (a full disk): the other ranks may be waiting
    // for it inside the run, so end them all rather than wait in MPI_Finalize.
    if (!ranks || ranks->size() == 1) throw;
    fmt::print(stderr, "regodem: error: {}\n", error.what());
    std::fflush(stderr);
    ranks->abort(exit_status::run_failed);
  }
  if (writer) fmt::print("{}\n", last_line);
  std::fflush(stdout);
  // An error thrown out of the run (writing an output) may be this rank's alone, with the
  // others waiting for it: end them all.
  if (ranks && ranks->size() > 1 && ending.thrown) {
    std::fflush(stderr);
    ranks->abort(ending.exit_code);
  }
  return ending.exit_code;
}

}  // namespace

int run_scenario(const RunOptions& options) { return execute(options, nullptr); }

int continue_run(const RunOptions& options, const ResumePoint& resume) { return execute(options, &resume); }

}  // namespace regodem::app
