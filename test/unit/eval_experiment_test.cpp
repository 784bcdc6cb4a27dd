#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "common/test_paths.h"
#include "tacs_graphs/common/config.h"
#include "tacs_graphs/eval/eval_report.h"
#include "tacs_graphs/pipeline/pipeline_config.h"

namespace tacs {
namespace {

TEST(EvalExperiment, MergesNestedOverridesIntoTheBase) {
  const nlohmann::json base = {{"odometry", {{"gicp", {{"num_threads", 2}, {"k_neighbors", 10}}}}},
                               {"walls", {{"max_gap", 0.5}}}};
  const nlohmann::json merged = mergeJson(base, {{"odometry", {{"gicp", {{"num_threads", 1}}}}}});
  EXPECT_EQ(merged["odometry"]["gicp"]["num_threads"], 1);
  EXPECT_EQ(merged["odometry"]["gicp"]["k_neighbors"], 10);
  EXPECT_EQ(merged["walls"]["max_gap"], 0.5);
}

TEST(EvalExperiment, ShippedMethodsLoadAndMakeValidConfigurations) {
  const std::string dir = test::sourceDir() + "/config";
  const nlohmann::json base = loadYamlAsJson(dir + "/default.yaml");
  size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir + "/eval")) {
    if (entry.path().extension() != ".yaml") continue;
    ++files;
    const std::string file = entry.path().filename().string();
    const auto methods = loadEvalMethods(entry.path().string());
    ASSERT_FALSE(methods.empty()) << file;
    for (const auto& m : methods) {
      PipelineConfig config;
      std::vector<std::string> unknown;
      EXPECT_NO_THROW(configFromJson(mergeJson(base, m.overrides), m.name, &config, &unknown))
          << file << ": " << m.name;
      EXPECT_TRUE(unknown.empty())
          << file << ": " << m.name << ": " << (unknown.empty() ? "" : unknown[0]);
    }
  }
  EXPECT_GE(files, 4u);  // methods.yaml and the ablations
}

TEST(EvalExperiment, BrokenMethodFileNamesTheEntry) {
  const std::string path = ::testing::TempDir() + "/bad_methods.yaml";
  std::ofstream(path) << "methods:\n  - label: no name\n";
  try {
    loadEvalMethods(path);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("methods[0].name"), std::string::npos) << e.what();
  }
}

TEST(EvalExperiment, PlansEveryWorldMethodAndTrialWithItsSeed) {
  const std::vector<EvalMethod> methods = {{"a", "A", {}}, {"b", "B", {}}};
  const auto runs = planRuns({"/w/lab.json", "/w/hall.json"}, methods, 3, "/out");
  ASSERT_EQ(runs.size(), 12u);
  EXPECT_EQ(runs[0].dir, "/out/runs/lab/a/trial1");
  EXPECT_EQ(runs[5].dir, "/out/runs/lab/b/trial3");
  EXPECT_EQ(runs[5].seed, 3u);
  EXPECT_EQ(runs[11].world_name, "hall");
}

TEST(EvalExperiment, TransformsWallsAndRoomsWithTheAlignment) {
  SceneGraph g;
  WallNode w;
  w.normal = Eigen::Vector3d::UnitX();
  w.d = -2.0;  // the plane x = 2
  w.endpoints = {Eigen::Vector2d(2, 0), Eigen::Vector2d(2, 3)};
  g.walls[0] = w;
  RoomNode r;
  r.center = Eigen::Vector3d(1, 1, 0);
  r.free_space = {Eigen::Vector2d(1, 1)};
  g.rooms[0] = r;
  const Pose3 T = poseFromXyzRpy(5, 0, 0, 0, 0, M_PI / 2);  // rotate 90 deg, then shift x by 5
  const SceneGraph t = transformSceneGraph(g, T);
  // x = 2 becomes y = 2 after the rotation; the shift moves it along x only.
  EXPECT_NEAR(t.walls.at(0).normal.y(), 1.0, 1e-12);
  EXPECT_NEAR(t.walls.at(0).d, -2.0, 1e-12);
  EXPECT_NEAR(t.walls.at(0).endpoints[1].x(), 5 - 3, 1e-12);
  EXPECT_NEAR(t.rooms.at(0).center.x(), 4.0, 1e-12);
  EXPECT_NEAR(t.rooms.at(0).free_space[0].y(), 1.0, 1e-12);
}

TEST(EvalExperiment, PairedDifferenceUsesTheTrialsBothMethodsHold) {
  // Trial 3 of b is missing: only trials 1, 2 and 4 pair up.
  const std::map<int, double> a = {{1, 1.0}, {2, 2.0}, {3, 3.0}, {4, 4.0}};
  const std::map<int, double> b = {{1, 1.5}, {2, 2.1}, {4, 4.4}};
  const PairedDifference d = pairedDifference(a, b);
  EXPECT_EQ(d.trials, 3u);
  EXPECT_EQ(d.a_lower, 3u);
  EXPECT_NEAR(d.mean, (0.5 + 0.1 + 0.4) / 3.0, 1e-12);
  // Sample sd of {0.5, 0.1, 0.4} is 0.208167; t(2) = 4.303.
  EXPECT_NEAR(d.ci95, 4.303 * 0.2081666 / std::sqrt(3.0), 1e-5);
  // The interval holds 0 here: three trials do not resolve a difference this spread.
  EXPECT_LT(d.mean - d.ci95, 0.0);
}

TEST(EvalExperiment, PairedDifferenceOfOneTrialHasNoInterval) {
  const std::map<int, double> a = {{1, 2.0}};
  const std::map<int, double> b = {{1, 1.0}, {2, 5.0}};
  const PairedDifference d = pairedDifference(a, b);
  EXPECT_EQ(d.trials, 1u);
  EXPECT_EQ(d.a_lower, 0u);
  EXPECT_DOUBLE_EQ(d.mean, -1.0);
  EXPECT_DOUBLE_EQ(d.ci95, 0.0);
}

}  // namespace
}  // namespace tacs
