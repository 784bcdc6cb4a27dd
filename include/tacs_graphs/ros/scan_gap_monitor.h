// Counts the scans that never reached a node: a cloud subscriber whose queue is full drops the
// oldest scans without a word, so a bag played faster than the node can process loses scans
// silently. The monitor learns the sensor period from the stamps it sees and reports every gap
// longer than 1.5 periods as missing scans. The period is the smallest median of a few
// consecutive steps seen so far: the median ignores stamp jitter, the minimum over time keeps the
// period of a node that falls behind for good (it then only receives every n-th scan).
#pragma once

#include <cstddef>
#include <deque>

namespace tacs {

class ScanGapMonitor {
 public:
  /// Takes the stamp of the next received scan (seconds) and returns how many scans are missing
  /// between it and the previous one (0 until the period is known, and for stamps that go back).
  size_t observe(double stamp);

  /// The sensor period (s); 0 while fewer than kMedianSteps steps have been seen.
  double period() const { return period_; }
  size_t missingTotal() const { return missing_total_; }

 private:
  static constexpr size_t kMedianSteps = 5;
  std::deque<double> recent_steps_;
  double period_ = 0.0;
  double last_stamp_ = 0.0;
  bool has_last_ = false;
  size_t missing_total_ = 0;
};

}  // namespace tacs
