// Helpers shared by the benchmarks.
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

#include "tacs_graphs/common/data_paths.h"
#include "tacs_graphs/common/heap.h"

namespace tacs::bench {

/// libgomp spins at every barrier by default, which on cores shared with other processes makes
/// two threads several times slower than one. The policy is read once at program start, so the
/// benchmark re-executes itself with OMP_WAIT_POLICY=passive unless the caller chose a policy.
inline void usePassiveOpenMpWait(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY")) return;
  setenv("OMP_WAIT_POLICY", "passive", 1);
  execv("/proc/self/exe", argv);  // returns only on failure: then run with the default policy
}

/// What every benchmark runs first: the OpenMP wait policy above, and the heap kept as the tools
/// and nodes keep it (common/heap.h), so a benchmark times what a run costs.
inline void setUpProcess(char** argv) {
  usePassiveOpenMpWait(argv);
  retainFreedHeapMemory();
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

/// The folder of data set `set` ("<dir>/<set>/"): under `data_dir` when one was given (--data),
/// else where tacs::findDataSet finds it; empty, after printing how to get it, when missing.
inline std::string dataSetDir(const std::string& set, const std::string& data_dir) {
  if (!data_dir.empty()) return data_dir + "/" + set + "/";
  const std::string dir = findDataSet(set, TACS_SOURCE_DIR);
  if (dir.empty()) std::cerr << missingDataSetMessage(set, TACS_SOURCE_DIR) << "\n";
  return dir;
}

}  // namespace tacs::bench
