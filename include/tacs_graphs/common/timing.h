// Wall-clock timing for per-stage statistics (timing.json, benchmarks), and the CPU time of the
// calling thread where waiting for a core must not count (t_FGO on a loaded machine).
#pragma once

#include <chrono>
#include <map>
#include <string>

namespace tacs {

/// Measures elapsed wall time since construction or the last restart().
class Stopwatch {
 public:
  Stopwatch() : start_(Clock::now()) {}
  void restart() { start_ = Clock::now(); }
  double elapsedMs() const {
    return std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
  }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_;
};

/// Measures the CPU time the calling thread used since construction: unlike Stopwatch, time the
/// thread spent waiting for a core (other threads, other processes) does not count.
class ThreadCpuStopwatch {
 public:
  ThreadCpuStopwatch() : start_ms_(nowMs()) {}
  double elapsedMs() const { return nowMs() - start_ms_; }

 private:
  static double nowMs();
  double start_ms_;
};

/// Accumulated time and call count per named stage.
class StageTimes {
 public:
  struct Entry {
    double total_ms = 0.0;
    double max_ms = 0.0;
    long calls = 0;
  };
  void add(const std::string& stage, double ms);
  const std::map<std::string, Entry>& entries() const { return entries_; }

 private:
  std::map<std::string, Entry> entries_;
};

}  // namespace tacs
