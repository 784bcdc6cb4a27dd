// The run folder is written beside its place and swapped in whole: no folder mixes two runs.
#include "tacs_graphs/pipeline/staged_run_folder.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace tacs {
namespace {

namespace fs = std::filesystem;

class StagedRunFolderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("tacs_staged_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
             "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  static void write(const fs::path& file, const std::string& text) { std::ofstream(file) << text; }
  static std::string read(const fs::path& file) {
    std::ifstream in(file);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  // The entries of the test's root folder: what a run leaves beside --out.
  size_t entriesBeside() const {
    return static_cast<size_t>(std::distance(fs::directory_iterator(root_), {}));
  }
  // The message of the error `dir` gets, or "" when it is accepted.
  static std::string errorOf(const fs::path& dir) {
    try {
      StagedRunFolder folder(dir.string());
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  }

  fs::path root_;
};

TEST_F(StagedRunFolderTest, ANewRunAppearsWholeAtTheCommit) {
  const fs::path out = root_ / "run";
  {
    StagedRunFolder folder(out.string() + "/");  // a trailing slash names the same folder
    EXPECT_EQ(folder.path(), out.string());
    write(fs::path(folder.stagingPath()) / "timing.json", "{}");
    EXPECT_FALSE(fs::exists(out));  // nothing in place before the commit
    folder.commit();
  }
  EXPECT_EQ(read(out / "timing.json"), "{}");
  EXPECT_EQ(entriesBeside(), 1u);  // the staging folder went with the swap
}

TEST_F(StagedRunFolderTest, AFormerRunIsReplacedWholeNotFileByFile) {
  const fs::path out = root_ / "run";
  fs::create_directories(out);
  write(out / "map.bt", "old map");
  write(out / "ground_truth.json", "old world");
  write(out / "trajectory_tum.txt", "old");
  StagedRunFolder folder(out.string());
  write(fs::path(folder.stagingPath()) / "trajectory_tum.txt", "new");
  folder.commit();
  EXPECT_EQ(read(out / "trajectory_tum.txt"), "new");
  EXPECT_FALSE(fs::exists(out / "map.bt"));
  EXPECT_FALSE(fs::exists(out / "ground_truth.json"));
  EXPECT_EQ(entriesBeside(), 1u);
}

TEST_F(StagedRunFolderTest, ARunThatFailsLeavesTheFolderAsItWas) {
  const fs::path out = root_ / "run";
  fs::create_directories(out);
  write(out / "map.bt", "old map");
  {
    StagedRunFolder folder(out.string());
    write(fs::path(folder.stagingPath()) / "map.bt.tmp", "half");
  }  // no commit: an exception or Ctrl-C unwound the run
  EXPECT_EQ(read(out / "map.bt"), "old map");
  EXPECT_EQ(entriesBeside(), 1u);
}

TEST_F(StagedRunFolderTest, UnwritablePlacesAreRefusedBeforeAnyWork) {
  write(root_ / "file", "x");
  EXPECT_NE(errorOf(root_ / "file").find("it is a file"), std::string::npos);
  EXPECT_NE(errorOf(root_ / "file" / "run").find("cannot create"), std::string::npos);
  EXPECT_NE(errorOf(".").find("not the current or parent folder"), std::string::npos);
  EXPECT_NE(errorOf("..").find("not the current or parent folder"), std::string::npos);
  // A folder of something else is never replaced.
  fs::create_directories(root_ / "photos");
  write(root_ / "photos" / "holiday.jpg", "x");
  EXPECT_NE(errorOf(root_ / "photos").find("not a run's"), std::string::npos);
  EXPECT_TRUE(fs::exists(root_ / "photos" / "holiday.jpg"));
  EXPECT_EQ(entriesBeside(), 2u);  // nothing staged beside them
  // An empty folder is fine.
  fs::create_directories(root_ / "empty");
  EXPECT_EQ(errorOf(root_ / "empty"), "");
}

}  // namespace
}  // namespace tacs
