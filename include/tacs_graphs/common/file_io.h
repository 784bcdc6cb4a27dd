// Small file helpers shared by the writers of run folders and maps.
#pragma once

#include <string>

namespace tacs {

/// Writes `content` to `path` through a temporary file in the same folder and a rename, so a
/// reader (or a crash) never sees a half-written file. Throws std::runtime_error naming the path.
void writeFileAtomically(const std::string& path, const std::string& content);

/// Creates `dir` and its parents if needed. Throws std::runtime_error naming the path.
void ensureDirectory(const std::string& dir);

}  // namespace tacs
