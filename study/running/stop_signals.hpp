// SIGINT and SIGTERM during a study: the handlers only count and remember the signal
// (all they may safely do); the runner's monitor thread reads them and decides. While
// a StopSignals exists its handlers are installed; the previous ones come back after.
#pragma once

#include <csignal>

namespace ballast {

class StopSignals {
 public:
  StopSignals();
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  // Signals received so far, and the last one (SIGINT or SIGTERM; 0 before any).
  static int count();
  static int last();

 private:
  struct sigaction old_int_, old_term_;
};

}  // namespace ballast
