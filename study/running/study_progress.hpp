// What a study shows while it runs. On a terminal: a live block, redrawn twice a
// second, with one line per run in flight (its stage and last settling step, from its
// log) and an overall line with an ETA, finished runs printed above it. Otherwise
// (a log file, a pipe, a batch job): plain lines, each run's log lines prefixed with
// its id. Thread-safe: runs report from their own threads.
#pragma once

#include <chrono>
#include <cstddef>
#include <map>
#include <mutex>
#include <ostream>
#include <string>

#include "study/archive/study_archive.hpp"

namespace ballast {

class ProgressBoard {
 public:
  // `to_do` runs will run now, `done` were recorded before; `jobs` side by side.
  ProgressBoard(std::ostream& out, bool live, std::size_t to_do, std::size_t done, int jobs);

  void started(const RunSpec& run, int threads);
  void log_line(const RunSpec& run, const std::string& line);
  void finished(const RunRecord& record);
  // A line for people, above the live block.
  void note(const std::string& text);
  // Live mode: redraws the block (the runner's monitor calls it twice a second).
  void redraw();
  // Removes the live block for good (before the summary).
  void close();
  std::size_t in_flight() const;

 private:
  struct Active {
    std::chrono::steady_clock::time_point start;
    std::string stage, step;
    long steps = 0;
    int threads = 1;
  };
  using Clock = std::chrono::steady_clock;

  std::string eta_text() const;
  std::string counts_text() const;
  void erase_block();
  void draw_block();

  std::ostream& out_;
  bool live_;
  std::size_t to_do_, done_before_, finished_ = 0, failed_ = 0;
  int jobs_;
  double finished_seconds_ = 0.0;  // wall time of the runs finished now
  std::map<std::string, Active> active_;
  int block_lines_ = 0;  // lines of the live block on screen
  bool closed_ = false;
  mutable std::mutex mutex_;
};

}  // namespace ballast
