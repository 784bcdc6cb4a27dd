// Helpers shared by the benchmarks.
#pragma once

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

#include "tacs_graphs/common/data_paths.h"
#include "tacs_graphs/common/process_setup.h"

namespace tacs::bench {

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
