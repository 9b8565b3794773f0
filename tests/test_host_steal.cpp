// Reading the hypervisor's steal time from /proc/stat (tests/bench/bed/host_steal.hpp).
#include <gtest/gtest.h>

#include "tests/bench/bed/host_steal.hpp"

using namespace ballast;

// A line as a 2-vCPU guest's kernel writes it (copied from a development VM):
// user nice system idle iowait irq softirq steal guest guest_nice.
TEST(HostSteal, ParsesTheAggregateCpuLine) {
  const auto t = parse_proc_stat(
      "cpu  4380687 1166 126041 5975129 2715 0 1770 153517 0 0\n"
      "cpu0 2198499 581 63163 2977840 1868 0 809 77172 0 0\n");
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(t->steal, 153517);
  EXPECT_EQ(t->idle, 5975129LL + 2715);
  EXPECT_EQ(t->total, 4380687LL + 1166 + 126041 + 5975129 + 2715 + 0 + 1770 + 153517);
}

TEST(HostSteal, RefusesWhatIsNotTheAggregateLine) {
  EXPECT_FALSE(parse_proc_stat("cpu0 2198499 581 63163 2977840 1868 0 809 77172 0 0").has_value());
  EXPECT_FALSE(parse_proc_stat("cpu  4380687 1166 126041 5975129 2715 0 1770").has_value());
  EXPECT_FALSE(parse_proc_stat("").has_value());
}

// The live counters only grow, and the steal is part of the busy time: a share in
// [0, 1] once a busy tick has passed (this test runs on Linux, where /proc/stat exists,
// and keeps a vCPU busy).
TEST(HostSteal, TheMeterGivesAShareOfTheTicksThatPassed) {
  const auto before = read_cpu_ticks();
  ASSERT_TRUE(before.has_value());
  StealMeter m;
  EXPECT_FALSE(m.share().has_value());  // nothing measured yet
  // A 10 ms tick of busy time passes within a few iterations (about 1 ms each); the
  // bound keeps a host whose counters never move from hanging the test.
  for (int k = 0; k < 10000 && !m.share().has_value(); ++k) {
    m.begin();
    volatile double x = 0.0;
    for (int i = 0; i < 1000000; ++i) x = x + 1.0;
    m.end();
    const auto now = read_cpu_ticks();
    ASSERT_TRUE(now.has_value());
    ASSERT_GE(now->total, before->total);
    ASSERT_GE(now->steal, before->steal);
  }
  ASSERT_TRUE(m.share().has_value());
  EXPECT_GE(*m.share(), 0.0);
  EXPECT_LE(*m.share(), 1.0);
}
