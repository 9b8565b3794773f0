// Pair lists made by the threads of a parallel region and joined in thread order.
//
// A neighbour build lists pairs (a, b) item by item: each ball's partner balls, each
// ball's walls. Items are independent, so each thread takes a contiguous range of
// them and lists their pairs in vectors of its own; joined in thread order, the
// lists are the serial ones whatever the thread count.
//
// The vectors live on each thread's stack until the join. Kept in a shared array
// of vectors instead, the threads' vector headers shared cache lines, and every
// append wrote one: the cores traded those lines thousands of times a build, and
// two threads took as long as one (docs/PERFORMANCE.md, "The neighbour build on two
// threads").
#pragma once

#include <omp.h>

#include <cstdint>
#include <vector>

#include "engine/types.hpp"

namespace ballast {

// scan(lo, hi, a, b) appends the pairs of items [lo, hi) to a and b, in item order.
template <class Scan>
void collect_pairs_in_order(Index n, const Scan& scan, std::vector<Index>& out_a,
                            std::vector<Index>& out_b) {
  const int threads = omp_get_max_threads();
  std::vector<std::vector<Index>> part_a(threads), part_b(threads);
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num(), team = omp_get_num_threads();
    const Index lo = Index(std::int64_t(n) * t / team),
                hi = Index(std::int64_t(n) * (t + 1) / team);
    std::vector<Index> a, b;
    scan(lo, hi, a, b);
    part_a[t] = std::move(a);
    part_b[t] = std::move(b);
  }
  std::size_t total = 0;
  for (const auto& p : part_a) total += p.size();
  out_a.clear();
  out_b.clear();
  out_a.reserve(total);
  out_b.reserve(total);
  for (int t = 0; t < threads; ++t) {
    out_a.insert(out_a.end(), part_a[t].begin(), part_a[t].end());
    out_b.insert(out_b.end(), part_b[t].begin(), part_b[t].end());
  }
}

}  // namespace ballast
