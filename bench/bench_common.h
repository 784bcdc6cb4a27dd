// Helpers shared by the benchmarks.
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>

namespace tacs::bench {

/// libgomp spins at every barrier by default, which on cores shared with other processes makes
/// two threads several times slower than one. The policy is read once at program start, so the
/// benchmark re-executes itself with OMP_WAIT_POLICY=passive unless the caller chose a policy.
inline void usePassiveOpenMpWait(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY")) return;
  setenv("OMP_WAIT_POLICY", "passive", 1);
  execv("/proc/self/exe", argv);  // returns only on failure: then run with the default policy
}

inline std::string openMpWaitPolicy() {
  const char* policy = std::getenv("OMP_WAIT_POLICY");
  return policy ? policy : "default (active spinning)";
}

/// The 1-minute load average: timings on shared cores depend on what else runs.
inline std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string load1;
  in >> load1;
  return load1;
}

}  // namespace tacs::bench
