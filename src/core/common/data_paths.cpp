#include "tacs_graphs/common/data_paths.h"

#include <cstdlib>
#include <filesystem>

namespace tacs {
namespace {

namespace fs = std::filesystem;

std::string envOrEmpty(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

}  // namespace

std::string userDataCacheDir() {
  std::string cache = envOrEmpty("XDG_CACHE_HOME");
  if (cache.empty()) cache = envOrEmpty("HOME") + "/.cache";
  return cache + "/tacs_graphs/data";
}

std::vector<std::string> dataSearchDirs(const std::string& source_dir) {
  const std::string explicit_dir = envOrEmpty("TACS_SHARED_DATA_DIR");
  if (!explicit_dir.empty()) return {explicit_dir};
  std::vector<std::string> dirs;
  std::error_code ec;
  for (fs::path dir = fs::weakly_canonical(source_dir, ec).parent_path();
       !dir.empty() && dir != dir.root_path(); dir = dir.parent_path()) {
    if (fs::is_directory(dir / "shared" / "data", ec)) {
      dirs.push_back((dir / "shared" / "data").string());
      break;
    }
  }
  dirs.push_back(userDataCacheDir());
  return dirs;
}

std::string findDataSet(const std::string& set, const std::string& source_dir) {
  std::error_code ec;
  for (const std::string& dir : dataSearchDirs(source_dir)) {
    if (fs::is_directory(fs::path(dir) / set, ec)) return dir + "/" + set + "/";
  }
  return "";
}

std::string missingDataSetMessage(const std::string& set, const std::string& source_dir) {
  std::string searched;
  for (const std::string& dir : dataSearchDirs(source_dir)) {
    searched += (searched.empty() ? "" : ", ") + dir;
  }
  return set + " missing: run scripts/get_test_data.sh (or set TACS_SHARED_DATA_DIR); looked in " +
         searched;
}

}  // namespace tacs
