// Thread shares that follow measured time, on top of a cost model.
//
// balanced_range (work_split.hpp) splits a loop by a static cost per item: counts of
// candidates, touching contacts and walls. On the sphere bench bed that model gave
// one thread 1.4 times the other's force-pass time in perf's samples
// (tests/bench/peers/thread_time.py, 2 threads), so the other waited at every
// barrier; and on a shared host one vCPU is often slower than the other for reasons
// no cost model sees. Like LAMMPS's `balance ... weight time`, a TimedSplit keeps
// each thread's measured speed (its share of the modelled cost per second, smoothed
// over steps) and hands out the next step's shares in proportion to it, so the
// threads finish together.
//
// Which thread computes an item never changes what is computed (every item's result
// is its own, and sums run in item order), so the split moves time, never bits.
#pragma once

#include <functional>
#include <vector>

namespace ballast {

class TimedSplit {
 public:
  // Each thread's weight (>= 0, not all zero) for the shares of update number
  // `update` (0 before the first) of a team of `threads`.
  using ShareRule = std::function<std::vector<double>(long update, int threads)>;

  // Serially, before the parallel region: sizes the split for `threads`, starting
  // from equal shares when the count changes.
  void prepare(int threads);
  // Whether the shares were made for a team of `threads` (balanced_range falls back
  // to equal shares otherwise).
  bool covers(int threads) const { return threads == threads_ && threads > 1; }
  // Fraction of the modelled cost before thread k's share: 0 for k = 0, 1 for
  // k = threads, nondecreasing.
  double cumulative(int k) const { return cumulative_[k]; }
  // In the region, by thread t only: the seconds its share took this step.
  void record(int t, double seconds) { seconds_[t] = seconds; }
  // Serially, after the region: folds this step's times into the speeds and remakes
  // the shares.
  void update();
  // Test hook: shares from `rule` instead of measured time, so that a determinism
  // test can force uneven or step-to-step changing shares without depending on the
  // clock. An empty rule returns to measured time from equal shares. It costs nothing
  // per item: balanced_range reads the same cumulative shares either way, and the
  // rule is called serially once per update().
  void force_shares(ShareRule rule);

 private:
  void apply_rule();  // cumulative_ from rule_(updates_, threads_)

  int threads_ = 0;
  bool measured_ = false;           // speeds hold a measurement
  std::vector<double> speed_;       // share of the cost per second, smoothed
  std::vector<double> seconds_;     // this step's, per thread (0: not recorded)
  std::vector<double> cumulative_;  // size threads + 1
  ShareRule rule_;                  // forced shares (test hook); empty: measured time
  long updates_ = 0;                // update() calls since the rule or the team changed
};

}  // namespace ballast
