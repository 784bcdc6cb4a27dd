// Where tests find the source tree and the shared real-data folder (set by CMake, overridable by
// the environment variables of the same names).
#pragma once

#include <cstdlib>
#include <string>

namespace tacs::test {

inline std::string sourceDir() {
  const char* env = std::getenv("TACS_SOURCE_DIR");
  return env ? env : TACS_SOURCE_DIR;
}

inline std::string sharedDataDir() {
  const char* env = std::getenv("TACS_SHARED_DATA_DIR");
  return env ? env : TACS_SHARED_DATA_DIR;
}

}  // namespace tacs::test
