// Every file in config/ (not its subfolders, which hold other formats) must load and validate, with no unknown key.
#include <gtest/gtest.h>

#include <filesystem>

#include "common/test_paths.h"
#include "tacs_graphs/pipeline/pipeline_config.h"

namespace tacs {
namespace {

TEST(ShippedConfigs, EveryFileLoadsAndValidates) {
  const std::filesystem::path dir = std::filesystem::path(test::sourceDir()) / "config";
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".yaml") continue;
    ++files;
    SCOPED_TRACE(entry.path().string());
    LoadedPipelineConfig loaded;
    ASSERT_NO_THROW(loaded = loadPipelineConfig(entry.path().string()));
    EXPECT_TRUE(loaded.unknown_keys.empty())
        << "unknown key: " << (loaded.unknown_keys.empty() ? "" : loaded.unknown_keys.front());
  }
  EXPECT_GE(files, 1) << "no YAML file found in " << dir;
}

}  // namespace
}  // namespace tacs
