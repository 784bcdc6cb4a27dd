#include "tacs_graphs/common/timing.h"

#include <time.h>

#include <algorithm>

namespace tacs {

double ThreadCpuStopwatch::nowMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

void StageTimes::add(const std::string& stage, double ms) {
  Entry& e = entries_[stage];
  e.total_ms += ms;
  e.max_ms = std::max(e.max_ms, ms);
  ++e.calls;
}

}  // namespace tacs
