#include "tacs_graphs/odometry/parallel.h"

#include <algorithm>
#include <atomic>

namespace tacs {

namespace {
std::atomic<int64_t> min_items_per_thread{2048};  // one per process, in the core library
}  // namespace

int64_t minItemsPerThread() { return min_items_per_thread.load(std::memory_order_relaxed); }

void setMinItemsPerThread(int64_t items) {
  min_items_per_thread.store(std::max<int64_t>(1, items), std::memory_order_relaxed);
}

}  // namespace tacs
