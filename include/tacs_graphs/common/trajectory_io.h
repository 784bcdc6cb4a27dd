// TUM trajectory files: one pose per line, "t x y z qx qy qz qw", space separated.
#pragma once

#include <stdexcept>
#include <string>

#include "tacs_graphs/common/types.h"

namespace tacs {

/// An unreadable or malformed trajectory file; what() names the file and line.
class TrajectoryIoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Writes `trajectory` with full double precision (stamps with 9 decimals).
void writeTum(const std::string& path, const Trajectory& trajectory);

/// Reads a TUM file. Blank lines and '#' comments are skipped; of several poses with the same
/// stamp the first is kept (MOCAP exports repeat rounded stamps). Throws TrajectoryIoError
/// "<path>: line N: <reason>". With `require_increasing`, a stamp before the previous line's is
/// such an error too (a trajectory to interpolate in must be sorted).
Trajectory readTum(const std::string& path, bool require_increasing = false);

}  // namespace tacs
