#include "study/running/stop_signals.hpp"

#include <atomic>

namespace ballast {

namespace {

// Lock-free atomics are async-signal-safe; static_assert below makes sure.
std::atomic<int> g_count{0};
std::atomic<int> g_last{0};
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void on_stop_signal(int sig) {
  g_last.store(sig);
  g_count.fetch_add(1);
}

}  // namespace

StopSignals::StopSignals() {
  g_count.store(0);
  g_last.store(0);
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;  // system calls in flight (file writes) carry on
  sigaction(SIGINT, &sa, &old_int_);
  sigaction(SIGTERM, &sa, &old_term_);
}

StopSignals::~StopSignals() {
  sigaction(SIGINT, &old_int_, nullptr);
  sigaction(SIGTERM, &old_term_, nullptr);
}

int StopSignals::count() {
  return g_count.load();
}

int StopSignals::last() {
  return g_last.load();
}

}  // namespace ballast
