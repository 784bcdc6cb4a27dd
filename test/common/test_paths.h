// Where tests find the source tree (set by CMake, overridable by the environment variable of the
// same name).
#pragma once

#include <cstdlib>
#include <string>

namespace tacs::test {

inline std::string sourceDir() {
  const char* env = std::getenv("TACS_SOURCE_DIR");
  return env ? env : TACS_SOURCE_DIR;
}

}  // namespace tacs::test
