// Where tests find the source tree and the shared real-data folder (set by CMake, overridable by
// the environment variables of the same names).
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>

namespace tacs::test {

inline std::string sourceDir() {
  const char* env = std::getenv("TACS_SOURCE_DIR");
  return env ? env : TACS_SOURCE_DIR;
}

/// The shared data folder: the environment variable, else ../shared/data beside the source tree,
/// else the nearest shared/data in a folder above it (a clone nested one level deeper).
inline std::string sharedDataDir() {
  const char* env = std::getenv("TACS_SHARED_DATA_DIR");
  if (env) return env;
  namespace fs = std::filesystem;
  if (fs::is_directory(TACS_SHARED_DATA_DIR)) return TACS_SHARED_DATA_DIR;
  for (fs::path dir = fs::path(sourceDir()).parent_path(); !dir.empty() && dir != dir.root_path();
       dir = dir.parent_path()) {
    if (fs::is_directory(dir / "shared" / "data")) return (dir / "shared" / "data").string();
  }
  return TACS_SHARED_DATA_DIR;
}

}  // namespace tacs::test
