#include "tacs_graphs/pipeline/scan_gap_monitor.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
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

void OverloadMonitor::arrived(double wall_s, size_t missing) {
  if (!window_start_) window_start_ = wall_s;
  ++arrived_;
  ++arrived_total_;
  missing_ += missing;
}

std::optional<std::string> OverloadMonitor::poll(double wall_s) {
  if (!window_start_ || wall_s - *window_start_ < window_s_) return std::nullopt;
  const double span = wall_s - *window_start_;
  const size_t arrived = arrived_, missing = missing_, produced = arrived + missing;
  window_start_ = wall_s;
  arrived_ = missing_ = 0;
  if (missing == 0) return std::nullopt;
  char text[320];
  std::snprintf(text, sizeof(text),
                "falling behind: %zu of %zu scans of the last %.0f s dropped (%.0f %%): "
                "%.1f scans/s handled of %.1f produced (%.2fx real time); the map is built from "
                "fewer scans (the drop ratio is saved in scene_graph.json, \"input\"). Play bags "
                "with play_bag, or lighten the odometry (odometry.preprocess.max_points)",
                missing, produced, span, 100.0 * missing / produced, arrived / span,
                produced / span, static_cast<double>(arrived) / produced);
  return std::string(text);
}

}  // namespace tacs
