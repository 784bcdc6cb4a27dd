// Where the real data sets are looked for: $TACS_SHARED_DATA_DIR alone, else shared/data beside
// the clone (or a folder above), then the per-user cache.
#include "tacs_graphs/common/data_paths.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

namespace tacs {
namespace {

namespace fs = std::filesystem;

// Sets (or unsets) an environment variable for one test and restores it afterwards.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::optional<std::string>& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    set(name, value);
  }
  ~ScopedEnv() { set(name_, old_); }

 private:
  static void set(const char* name, const std::optional<std::string>& value) {
    if (value) {
      setenv(name, value->c_str(), 1);
    } else {
      unsetenv(name);
    }
  }

  const char* name_;
  std::optional<std::string> old_;
};

// root/work/clone (the source tree), root/shared/data/beside, root/cache/tacs_graphs/data/cached.
class DataPathsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::remove_all(root_);
    fs::create_directories(clone_);
    fs::create_directories(root_ + "/shared/data/beside");
    fs::create_directories(root_ + "/cache/tacs_graphs/data/cached");
  }
  void TearDown() override { fs::remove_all(root_); }

  // Canonical, as the resolver returns the folders it finds above the (canonical) clone.
  const std::string root_ =
      fs::weakly_canonical(fs::path(::testing::TempDir()) / "tacs_data_paths_test").string();
  const std::string clone_ = root_ + "/work/clone";
  ScopedEnv no_explicit_dir_{"TACS_SHARED_DATA_DIR", std::nullopt};
  ScopedEnv cache_{"XDG_CACHE_HOME", root_ + "/cache"};
};

TEST_F(DataPathsTest, SharedDataAboveTheCloneThenTheUserCache) {
  EXPECT_EQ(dataSearchDirs(clone_),
            (std::vector<std::string>{root_ + "/shared/data", root_ + "/cache/tacs_graphs/data"}));
  EXPECT_EQ(findDataSet("beside", clone_), root_ + "/shared/data/beside/");
  EXPECT_EQ(findDataSet("cached", clone_), root_ + "/cache/tacs_graphs/data/cached/");
  EXPECT_EQ(findDataSet("absent", clone_), "");
}

TEST_F(DataPathsTest, TheExplicitFolderIsTheOnlyOneLookedAt) {
  const ScopedEnv explicit_dir("TACS_SHARED_DATA_DIR", root_ + "/shared/data");
  EXPECT_EQ(dataSearchDirs(clone_), std::vector<std::string>{root_ + "/shared/data"});
  EXPECT_EQ(findDataSet("beside", clone_), root_ + "/shared/data/beside/");
  EXPECT_EQ(findDataSet("cached", clone_), "");
}

TEST_F(DataPathsTest, CacheDefaultsToHomeDotCache) {
  const ScopedEnv no_xdg("XDG_CACHE_HOME", std::nullopt);
  const ScopedEnv home("HOME", root_);
  EXPECT_EQ(userDataCacheDir(), root_ + "/.cache/tacs_graphs/data");
}

TEST_F(DataPathsTest, MissingSetMessageNamesTheSetTheCommandAndTheFolders) {
  const std::string message = missingDataSetMessage("absent", clone_);
  EXPECT_EQ(message.rfind("absent missing: run scripts/get_test_data.sh", 0), 0u) << message;
  EXPECT_NE(message.find(root_ + "/cache/tacs_graphs/data"), std::string::npos) << message;
}

}  // namespace
}  // namespace tacs
