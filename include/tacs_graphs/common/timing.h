// Wall-clock timing for per-stage statistics (timing.json, benchmarks).
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
