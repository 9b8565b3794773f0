// Thread shares that follow measured time (engine/timed_split.hpp): they settle where
// the threads take equal time, one preempted step moves them little, and the ranges
// balanced_range hands out with them still tile the loop exactly; forced shares (the
// determinism tests' hook) follow their rule alone.
#include <gtest/gtest.h>
#include <omp.h>

#include <stdexcept>
#include <utility>
#include <vector>

#include "engine/timed_split.hpp"
#include "engine/work_split.hpp"

namespace ballast {
namespace {

double share(const TimedSplit& s, int t) {
  return s.cumulative(t + 1) - s.cumulative(t);
}

// One step in which thread t needs seconds_per_share[t] for the whole cost.
void step(TimedSplit& s, const std::vector<double>& seconds_per_share) {
  for (int t = 0; t < int(seconds_per_share.size()); ++t)
    s.record(t, share(s, t) * seconds_per_share[t]);
  s.update();
}

TEST(TimedSplit, StartsEqualAndResetsWhenTheTeamChanges) {
  TimedSplit s;
  s.prepare(2);
  EXPECT_TRUE(s.covers(2));
  EXPECT_FALSE(s.covers(3));
  EXPECT_FALSE(s.covers(1));  // one thread needs no split
  step(s, {1.0, 3.0});
  EXPECT_NE(share(s, 0), 0.5);
  s.prepare(3);
  for (int t = 0; t < 3; ++t) EXPECT_DOUBLE_EQ(share(s, t), 1.0 / 3.0);
  EXPECT_EQ(s.cumulative(3), 1.0);
}

TEST(TimedSplit, SharesSettleWhereThreadsTakeEqualTime) {
  // Thread 1 is three times slower: equal time means shares 3/4 and 1/4.
  TimedSplit s;
  s.prepare(2);
  for (int k = 0; k < 400; ++k) step(s, {1.0, 3.0});
  EXPECT_NEAR(share(s, 0), 0.75, 1e-6);
  EXPECT_NEAR(share(s, 0) * 1.0, share(s, 1) * 3.0, 1e-6);
  EXPECT_EQ(s.cumulative(0), 0.0);
  EXPECT_EQ(s.cumulative(2), 1.0);
}

TEST(TimedSplit, OnePreemptedStepMovesTheSharesLittle) {
  TimedSplit s;
  s.prepare(2);
  for (int k = 0; k < 50; ++k) step(s, {1.0, 1.0});
  ASSERT_NEAR(share(s, 0), 0.5, 1e-12);
  step(s, {10.0, 1.0});  // thread 0 descheduled for most of a step
  // Its speed may fall by at most half, weighted 1/20: a share of 0.975/1.975.
  EXPECT_NEAR(share(s, 0), 0.975 / 1.975, 1e-12);
  for (int k = 0; k < 400; ++k) step(s, {1.0, 1.0});
  EXPECT_NEAR(share(s, 0), 0.5, 1e-6);
}

TEST(TimedSplit, AStepWithoutEveryThreadsTimeKeepsTheShares) {
  TimedSplit s;
  s.prepare(2);
  for (int k = 0; k < 100; ++k) step(s, {1.0, 3.0});
  const double before = share(s, 0);
  s.record(0, 0.5);  // thread 1 recorded nothing (a pass that ran serially)
  s.update();
  EXPECT_EQ(share(s, 0), before);
}

TEST(TimedSplit, BalancedRangeTilesTheLoopAtTheMeasuredShares) {
  TimedSplit s;
  s.prepare(2);
  for (int k = 0; k < 400; ++k) step(s, {1.0, 3.0});  // shares 3/4, 1/4
  const Index n = 1000;
  // Item k costs k + 1, so that the boundary is not at 3/4 of the items.
  const auto prefix = [](Index k) { return long(k) * (k + 1) / 2; };
  std::vector<std::pair<Index, Index>> ranges(2);
  int team = 0;
#pragma omp parallel num_threads(2)
  {
    ranges[omp_get_thread_num()] = balanced_range(n, prefix, &s);
#pragma omp single
    team = omp_get_num_threads();
  }
  ASSERT_EQ(team, 2);
  EXPECT_EQ(ranges[0].first, 0);
  EXPECT_EQ(ranges[0].second, ranges[1].first);
  EXPECT_EQ(ranges[1].second, n);
  // The boundary is the first item whose prefix reaches 3/4 of the total cost (the
  // shares are 3/4 to 1e-6).
  const double three_quarters = 0.75 * double(prefix(n));
  const Index boundary = ranges[0].second;
  EXPECT_GE(double(prefix(boundary)), three_quarters * (1.0 - 1e-5));
  EXPECT_LT(double(prefix(boundary - 1)), three_quarters * (1.0 + 1e-5));
  EXPECT_GT(boundary, 800);  // well past 3/4 of the items: the costs grow with k
  // A split made for another team size is ignored: equal shares of the cost.
  TimedSplit three;
  three.prepare(3);
#pragma omp parallel num_threads(2)
  ranges[omp_get_thread_num()] = balanced_range(n, prefix, &three);
  EXPECT_GE(prefix(ranges[0].second), prefix(n) / 2);
  EXPECT_LT(prefix(ranges[0].second - 1), prefix(n) / 2);
  EXPECT_EQ(ranges[1].second, n);
}

// The test hook (TimedSplit::force_shares) that determinism tests use: the shares are
// the rule's at every update, whatever the threads measured, and empty ones are fine.
// Mutations that must break these (tests/mutations.tsv): update() not advancing the
// rule's update count, and the negative-weight check dropped; each failed here.
TEST(TimedSplit, ForcedSharesFollowTheRuleNotTheClock) {
  TimedSplit s;
  s.prepare(3);
  s.force_shares([](long update, int threads) {
    std::vector<double> w(threads, 1.0);
    w[update % threads] = 0.0;  // an empty share, a different thread at each update
    w[(update + 1) % threads] = 2.0;
    return w;
  });
  EXPECT_TRUE(s.covers(3));
  for (long update = 0; update < 4; ++update) {
    SCOPED_TRACE(update);
    EXPECT_EQ(share(s, int(update % 3)), 0.0);
    EXPECT_DOUBLE_EQ(share(s, int((update + 1) % 3)), 2.0 / 3.0);
    EXPECT_EQ(s.cumulative(3), 1.0);
    step(s, {1.0, 5.0, 25.0});  // times that would move measured shares a lot
  }
  // The rule applies to a new team from its first step; no rule: equal shares again.
  s.prepare(2);
  EXPECT_EQ(share(s, 0), 0.0);
  s.force_shares({});
  EXPECT_EQ(share(s, 0), 0.5);
  step(s, {1.0, 3.0});
  EXPECT_GT(share(s, 0), 0.5);  // measured time again
}

TEST(TimedSplit, ForcedSharesRefuseAWrongRule) {
  TimedSplit s;
  s.prepare(2);
  EXPECT_THROW(s.force_shares([](long, int) { return std::vector<double>{1.0}; }),
               std::invalid_argument);
  EXPECT_THROW(s.force_shares([](long, int) {
    return std::vector<double>{0.0, 0.0};
  }),
               std::invalid_argument);
  EXPECT_THROW(s.force_shares([](long, int) {
    return std::vector<double>{2.0, -1.0};
  }),
               std::invalid_argument);
}

}  // namespace
}  // namespace ballast
