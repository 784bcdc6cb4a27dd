// The run folder of docs/DESIGN.md written beside its place and swapped in whole: a run that
// fails, is interrupted or cannot write leaves the folder as it was, never one that mixes two runs
// (a new trajectory beside an old map.bt, a bag run beside a former world run's ground truth).
#pragma once

#include <string>

namespace tacs {

class StagedRunFolder {
 public:
  /// Checks `dir` before any work: throws std::runtime_error naming it when it is a file, lies
  /// under a file, cannot be created or written, or holds files that are not a run's (a folder
  /// given by mistake is never replaced). Creates the staging folder beside it.
  explicit StagedRunFolder(const std::string& dir);
  /// Removes the staging folder unless committed.
  ~StagedRunFolder();
  StagedRunFolder(const StagedRunFolder&) = delete;
  StagedRunFolder& operator=(const StagedRunFolder&) = delete;

  /// Where the run is written now.
  const std::string& stagingPath() const { return staging_; }
  const std::string& path() const { return dir_; }

  /// Replaces the folder with the staged run (a former run is removed). Throws
  /// std::runtime_error when the swap fails; the former run is then put back.
  void commit();

  /// True when every entry of `dir` is a file a run writes (an empty folder is one).
  static bool looksLikeRunFolder(const std::string& dir);

 private:
  std::string dir_;
  std::string staging_;
  bool committed_ = false;
};

}  // namespace tacs
