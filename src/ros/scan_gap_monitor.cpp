#include "tacs_graphs/ros/scan_gap_monitor.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace tacs {

size_t ScanGapMonitor::observe(double stamp) {
  if (!has_last_ || stamp <= last_stamp_) {
    // The first scan, or a stamp going back (the caller skips it): no step to learn from.
    last_stamp_ = stamp;
    has_last_ = true;
    return 0;
  }
  const double step = stamp - last_stamp_;
  last_stamp_ = stamp;
  // The gap is measured against the period known before this step, not against itself.
  const double known_period = period_;
  recent_steps_.push_back(step);
  if (recent_steps_.size() > kMedianSteps) recent_steps_.pop_front();
  if (recent_steps_.size() == kMedianSteps) {
    std::vector<double> sorted(recent_steps_.begin(), recent_steps_.end());
    std::nth_element(sorted.begin(), sorted.begin() + kMedianSteps / 2, sorted.end());
    const double median = sorted[kMedianSteps / 2];
    period_ = period_ > 0.0 ? std::min(period_, median) : median;
  }
  if (known_period <= 0.0 || step < 1.5 * known_period) return 0;
  const size_t missing = static_cast<size_t>(std::lround(step / known_period)) - 1;
  missing_total_ += missing;
  return missing;
}

}  // namespace tacs
