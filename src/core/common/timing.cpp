#include "tacs_graphs/common/timing.h"

#include <algorithm>

namespace tacs {

void StageTimes::add(const std::string& stage, double ms) {
  Entry& e = entries_[stage];
  e.total_ms += ms;
  e.max_ms = std::max(e.max_ms, ms);
  ++e.calls;
}

}  // namespace tacs
