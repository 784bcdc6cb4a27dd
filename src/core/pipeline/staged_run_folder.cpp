#include "tacs_graphs/pipeline/staged_run_folder.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace tacs {

namespace fs = std::filesystem;

namespace {

// The files of a run folder (docs/DESIGN.md), and the temporaries they are written through.
bool isRunFile(const fs::path& name) {
  static const char* const kFiles[] = {"trajectory_tum.txt",
                                       "odometry_tum.txt",
                                       "scene_graph.json",
                                       "timing.json",
                                       "config.json",
                                       "map.pcd",
                                       "map.bt",
                                       "topdown.png",
                                       "ground_truth_tum.txt",
                                       "ground_truth.json",
                                       "reference_tum.txt",
                                       "localization.json",
                                       "session_graph.json"};
  const std::string s = name.string();
  if (name.extension() == ".tmp") return true;
  return std::any_of(std::begin(kFiles), std::end(kFiles), [&](const char* f) { return s == f; });
}

[[noreturn]] void fail(const std::string& dir, const std::string& why) {
  throw std::runtime_error("cannot write the run to " + dir + ": " + why);
}

}  // namespace

bool StagedRunFolder::looksLikeRunFolder(const std::string& dir) {
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    if (!e.is_regular_file(ec) || !isRunFile(e.path().filename())) return false;
  }
  return !ec;
}

StagedRunFolder::StagedRunFolder(const std::string& dir) {
  fs::path p = fs::path(dir).lexically_normal();
  if (!p.has_filename() && p.has_parent_path()) p = p.parent_path();  // "out/"
  if (p.empty() || p.filename() == "." || p.filename() == "..") {
    fail(dir, "give a folder of its own, not the current or parent folder");
  }
  dir_ = p.string();
  std::error_code ec;
  const fs::file_status st = fs::status(p, ec);
  if (fs::exists(st)) {
    if (!fs::is_directory(st)) fail(dir_, "it is a file, not a folder");
    if (!looksLikeRunFolder(dir_)) {
      fail(dir_, "it holds files that are not a run's; give a new or empty folder");
    }
    if (::access(dir_.c_str(), W_OK) != 0) fail(dir_, "no permission to replace it");
  }
  const fs::path parent = p.has_parent_path() ? p.parent_path() : fs::path(".");
  fs::create_directories(parent, ec);
  if (ec) fail(dir_, "cannot create " + parent.string() + ": " + ec.message());
  staging_ =
      (parent / ("." + p.filename().string() + ".partial-" + std::to_string(::getpid()))).string();
  fs::remove_all(staging_, ec);  // left by a killed run of the same pid
  if (!fs::create_directory(staging_, ec) || ec) {
    fail(dir_, "cannot create a folder in " + parent.string() + ": " +
                   (ec ? ec.message() : std::string("it already exists")));
  }
  if (::access(staging_.c_str(), W_OK) != 0) fail(dir_, "no permission to write in it");
}

StagedRunFolder::~StagedRunFolder() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);
}

void StagedRunFolder::commit() {
  std::error_code ec;
  const std::string former = staging_ + ".former";
  const bool had_run = fs::exists(dir_, ec);
  if (had_run) {
    fs::rename(dir_, former, ec);
    if (ec) fail(dir_, "cannot move the former run aside: " + ec.message());
  }
  fs::rename(staging_, dir_, ec);
  if (ec) {
    std::error_code back;
    if (had_run) fs::rename(former, dir_, back);
    fail(dir_, "cannot move the run into place: " + ec.message());
  }
  committed_ = true;
  if (had_run) fs::remove_all(former, ec);
}

}  // namespace tacs
