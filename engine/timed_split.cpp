#include "engine/timed_split.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace ballast {

namespace {
// Weight of one step's measurement in the smoothed speed: a time constant of about
// 20 steps, a few milliseconds, so that one preempted step moves the shares little.
constexpr double kSmoothing = 0.05;
// One step's speed counts at most double or half the smoothed one: a thread that was
// descheduled for a millisecond measures a speed ten times too low.
constexpr double kMaxJump = 2.0;
}  // namespace

void TimedSplit::prepare(int threads) {
  if (threads == threads_) return;
  threads_ = threads;
  measured_ = false;
  speed_.assign(threads, 1.0);
  seconds_.assign(threads, 0.0);
  cumulative_.resize(threads + 1);
  for (int k = 0; k <= threads; ++k) cumulative_[k] = double(k) / threads;
  updates_ = 0;
  if (rule_) apply_rule();
}

void TimedSplit::force_shares(ShareRule rule) {
  rule_ = std::move(rule);
  const int threads = threads_;
  threads_ = 0;  // prepare() starts again from equal shares, or from the rule's
  try {
    if (threads > 0) prepare(threads);
  } catch (...) {
    rule_ = nullptr;  // a refused rule leaves measured time from equal shares
    throw;
  }
}

void TimedSplit::apply_rule() {
  if (threads_ <= 1) return;
  const std::vector<double> w = rule_(updates_, threads_);
  double total = 0.0;
  bool valid = int(w.size()) == threads_;
  for (double v : w) {
    valid = valid && v >= 0.0;  // and not NaN
    total += v;
  }
  if (!valid || !(total > 0.0) || !std::isfinite(total))
    throw std::invalid_argument(
        "TimedSplit::force_shares: one finite weight >= 0 per thread, not all zero");
  double sum = 0.0;
  for (int t = 0; t < threads_; ++t) {
    sum += w[t];
    cumulative_[t + 1] = t + 1 == threads_ ? 1.0 : sum / total;
  }
}

void TimedSplit::update() {
  if (threads_ <= 1) return;
  if (rule_) {
    ++updates_;
    apply_rule();
    return;
  }
  for (int t = 0; t < threads_; ++t)
    if (!(seconds_[t] > 0.0)) return;  // a thread did not record: keep the shares
  for (int t = 0; t < threads_; ++t) {
    const double share = cumulative_[t + 1] - cumulative_[t];
    const double speed = share / seconds_[t];
    if (!measured_) {
      speed_[t] = speed;
    } else {
      const double jump = std::clamp(speed / speed_[t], 1.0 / kMaxJump, kMaxJump);
      speed_[t] *= 1.0 + kSmoothing * (jump - 1.0);
    }
    seconds_[t] = 0.0;
  }
  measured_ = true;
  double total = 0.0;
  for (double v : speed_) total += v;
  double sum = 0.0;
  cumulative_[0] = 0.0;
  for (int t = 0; t < threads_; ++t) {
    sum += speed_[t];
    cumulative_[t + 1] = t + 1 == threads_ ? 1.0 : sum / total;
  }
}

}  // namespace ballast
