// Deterministic OpenMP reductions: each thread sums a contiguous block, then the blocks are added
// in thread order, so results depend only on the thread count (the offline runs are repeatable).
#pragma once

#include <omp.h>

#include <cstdint>
#include <vector>

namespace tacs {

/// num_threads <= 0 means the OpenMP default.
inline int resolveThreads(int num_threads) {
  return num_threads > 0 ? num_threads : omp_get_max_threads();
}

/// Calls fn(i, partial) for i in [0, n) with a per-thread accumulator and returns their sum.
/// Acc must be default-constructible to zero and have operator+=.
template <class Acc, class Fn>
Acc parallelReduce(int64_t n, int num_threads, const Fn& fn) {
  const int threads = resolveThreads(num_threads);
  std::vector<Acc> partial(threads);
#pragma omp parallel num_threads(threads)
  {
    Acc& mine = partial[omp_get_thread_num()];
#pragma omp for schedule(static)
    for (int64_t i = 0; i < n; ++i) fn(i, mine);
  }
  Acc total;
  for (const Acc& p : partial) total += p;
  return total;
}

}  // namespace tacs
