// Deterministic OpenMP reductions. The index range is cut into fixed blocks that threads take
// dynamically (a thread descheduled on a busy machine does not hold up a large static share);
// each block has its own partial sum and the partials are added in block order, so the result
// is bit-identical for any thread count (offline runs are repeatable).
#pragma once

#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace tacs {

/// num_threads <= 0 means the OpenMP default.
inline int resolveThreads(int num_threads) {
  return num_threads > 0 ? num_threads : omp_get_max_threads();
}

/// Items per thread below which a loop does not wake another thread: waking one costs tens of
/// microseconds, a few hundred points' worth of searches, and far more when the cores are busy
/// with other work. 2048 by default, for the node suite, where six nodes share the cores: with
/// 512, the odometry node lost 832 of large_hall's 3659 scans at 4x playback (32 with 2048).
/// tacs_offline, alone on the machine, sets 512: a 2.8k-point VLP-16 scan is then split
/// (open_office read from a bag: 70 -> 83-94 scans/s; 256 gains nothing more).
int64_t minItemsPerThread();
void setMinItemsPerThread(int64_t items);

/// Threads worth starting for n items (at least minItemsPerThread() each).
inline int threadsFor(int64_t n, int num_threads) {
  const int64_t useful = std::max<int64_t>(1, n / minItemsPerThread());
  return static_cast<int>(std::min<int64_t>(resolveThreads(num_threads), useful));
}

/// Calls fn(i, partial) for i in [0, n) and returns the sum of the partials. Acc must be
/// default-constructible to zero and have operator+=.
template <class Acc, class Fn>
Acc parallelReduce(int64_t n, int num_threads, const Fn& fn) {
  constexpr int64_t kBlock = 512;
  const int64_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<Acc> partial(static_cast<size_t>(blocks));
#pragma omp parallel for num_threads(threadsFor(n, num_threads)) schedule(dynamic, 1)
  for (int64_t b = 0; b < blocks; ++b) {
    const int64_t end = std::min(n, (b + 1) * kBlock);
    for (int64_t i = b * kBlock; i < end; ++i) fn(i, partial[b]);
  }
  Acc total;
  for (const Acc& p : partial) total += p;
  return total;
}

/// Calls fn(i) for i in [0, n) in blocks taken dynamically by the threads.
template <class Fn>
void parallelFor(int64_t n, int num_threads, const Fn& fn) {
  constexpr int64_t kBlock = 256;
  const int64_t blocks = (n + kBlock - 1) / kBlock;
#pragma omp parallel for num_threads(threadsFor(n, num_threads)) schedule(dynamic, 1)
  for (int64_t b = 0; b < blocks; ++b) {
    const int64_t end = std::min(n, (b + 1) * kBlock);
    for (int64_t i = b * kBlock; i < end; ++i) fn(i);
  }
}

}  // namespace tacs
