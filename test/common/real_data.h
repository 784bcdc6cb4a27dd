// Real data sets in tests: found through tacs::findDataSet (see tacs_graphs/common/data_paths.h).
// A missing set skips the test with the command that gets it; with TACS_REQUIRE_REAL_DATA=1 (CI)
// it fails the test instead, so real-data tests are never skipped unnoticed.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "common/test_paths.h"
#include "tacs_graphs/common/data_paths.h"

namespace tacs::test {

inline bool realDataRequired() {
  const char* env = std::getenv("TACS_REQUIRE_REAL_DATA");
  return env && std::string(env) != "" && std::string(env) != "0";
}

// Void, because GTEST_SKIP() returns from the function it is in.
inline void reportMissingDataSet(const std::string& set) {
  const std::string message = missingDataSetMessage(set, sourceDir());
  if (realDataRequired()) {
    ADD_FAILURE() << message << " [TACS_REQUIRE_REAL_DATA=1]";
    return;
  }
  GTEST_SKIP() << message;
}

/// The folder of data set `set` ("<dir>/<set>/"); empty, with the test skipped or failed, when
/// it is missing.
inline std::string dataSet(const std::string& set) {
  const std::string dir = findDataSet(set, sourceDir());
  if (dir.empty()) reportMissingDataSet(set);
  return dir;
}

}  // namespace tacs::test

/// Declares `dir`, the folder of data set `set`, or returns from the test when the set is missing.
#define TACS_DATA_SET_OR_SKIP(dir, set)               \
  const std::string dir = ::tacs::test::dataSet(set); \
  if (dir.empty()) return
