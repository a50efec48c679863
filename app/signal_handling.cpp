#include "signal_handling.hpp"

#include <csignal>
#include <stdexcept>

#include <fmt/format.h>

namespace regodem::app {
namespace {

// A signal handler may only touch lock-free atomics (and volatile sig_atomic_t).
static_assert(std::atomic<bool>::is_always_lock_free);
static_assert(std::atomic<int>::is_always_lock_free);

std::atomic<bool> stop_requested{false};
std::atomic<int> received_signal{0};

std::atomic<int> signal_count{0};

void count_signal(int signal_number) {
  received_signal.store(signal_number);
  signal_count.fetch_add(1);
}

void request_stop(int signal_number) {
  received_signal.store(signal_number);
  stop_requested.store(true);
}

void install(int signal_number, void (*handler)(int), int flags) {
  struct sigaction action {};
  action.sa_handler = handler;
  sigemptyset(&action.sa_mask);
  action.sa_flags = flags;
  if (::sigaction(signal_number, &action, nullptr) != 0) {
    throw std::runtime_error(fmt::format("cannot install the handler for signal {}", signal_number));
  }
}

}  // namespace

const std::atomic<bool>& install_stop_request_handlers() {
  install(SIGINT, request_stop, SA_RESTART);
  install(SIGTERM, request_stop, SA_RESTART);
  return stop_requested;
}

const std::atomic<int>& install_signal_counter() {
  install(SIGINT, count_signal, SA_RESTART);
  install(SIGTERM, count_signal, SA_RESTART);
  return signal_count;
}

int stop_signal() { return received_signal.load(); }

}  // namespace regodem::app
