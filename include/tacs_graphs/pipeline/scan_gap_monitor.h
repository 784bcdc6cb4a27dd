// Counts the scans that never reached a node: a cloud subscriber whose queue is full drops the
// oldest scans without a word, so a bag played faster than the node can process loses scans
// silently. The monitor learns the sensor period from the stamps it sees and reports every gap
// longer than 1.5 periods as missing scans. The period is the smallest median of a few
// consecutive steps seen so far: the median ignores stamp jitter, the minimum over time keeps the
// period of a node that falls behind for good (it then only receives every n-th scan).
#pragma once

#include <cstddef>
#include <deque>
#include <optional>
#include <string>

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

/// Whether the odometry keeps up, over windows of wall time: the scans that arrived (each is
/// handled, in order) and those missing before them (ScanGapMonitor). A window with missing scans
/// closes with one report: the drop ratio and the rate handled against the rate produced.
class OverloadMonitor {
 public:
  explicit OverloadMonitor(double window_s = 10.0) : window_s_(window_s) {}

  /// A scan arrived at wall time `wall_s`, with `missing` scans lost before it.
  void arrived(double wall_s, size_t missing);

  /// The report of the window that has closed by `wall_s`, when scans went missing in it.
  std::optional<std::string> poll(double wall_s);

  size_t arrivedTotal() const { return arrived_total_; }

 private:
  double window_s_;
  std::optional<double> window_start_;
  size_t arrived_ = 0, missing_ = 0, arrived_total_ = 0;
};

}  // namespace tacs
