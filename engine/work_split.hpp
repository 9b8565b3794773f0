// Splitting a loop between the threads of a parallel region by work rather than by
// count. `omp for schedule(static)` hands each thread the same number of balls or
// bodies; in a settled bed numbered bottom to top (as the packings numbered them
// before they were numbered across the bed's smallest section, sphere_packing.hpp)
// the lower half has the base and the denser contacts, so one thread waited for the
// other at every barrier (1.64x on two threads); any numbering leaves some such
// unevenness, and the walls' contacts fall to the shares that hold their balls. Here
// thread t takes the items whose cumulative cost lies in [t, t+1)·total/threads.
// The split changes which thread computes an item, never what it computes, so the
// results stay bit-identical for any thread count.
#pragma once

#include <omp.h>

#include <cmath>
#include <utility>

#include "engine/timed_split.hpp"
#include "engine/types.hpp"

namespace ballast {

// The calling thread's share [lo, hi) of items [0, n). prefix(k) is the cost of
// items [0, k): integer, nondecreasing, prefix(0) = 0. Outside a parallel region
// (one thread) it is [0, n). With a `split` made for this team (timed_split.hpp),
// thread k's share of the cost is the split's measured one instead of 1/threads.
template <class Prefix>
std::pair<Index, Index> balanced_range(Index n, const Prefix& prefix,
                                       const TimedSplit* split = nullptr) {
  const long threads = omp_get_num_threads(), t = omp_get_thread_num();
  const long total = prefix(n);
  const bool timed = split != nullptr && split->covers(int(threads));
  // First item whose prefix reaches `target`: the boundaries are the same whichever
  // thread computes them, so the shares tile [0, n) exactly.
  const auto boundary = [&](long k) -> Index {
    if (k <= 0) return 0;
    if (k >= threads) return n;
    const long target =
        timed ? std::lround(double(total) * split->cumulative(int(k))) : total * k / threads;
    Index lo = 0, hi = n;
    while (lo < hi) {
      const Index mid = lo + (hi - lo) / 2;
      if (prefix(mid) < target)
        lo = mid + 1;
      else
        hi = mid;
    }
    return lo;
  };
  return {boundary(t), boundary(t + 1)};
}

}  // namespace ballast
