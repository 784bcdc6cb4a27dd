#include <gtest/gtest.h>

#include <random>

#include "tacs_graphs/backend/factor_graph.h"
#include "tacs_graphs/common/config.h"

namespace tacs {
namespace {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

// A robot driving around a 10 x 6 m rectangle, one keyframe per metre, heading along the path.
std::vector<Pose3> rectangleLoop() {
  std::vector<Pose3> poses;
  const std::vector<Eigen::Vector2d> corners = {{0, 0}, {10, 0}, {10, 6}, {0, 6}, {0, 0}};
  for (size_t s = 0; s + 1 < corners.size(); ++s) {
    const Eigen::Vector2d a = corners[s], b = corners[s + 1];
    const int steps = static_cast<int>((b - a).norm());
    const double yaw = std::atan2((b - a).y(), (b - a).x());
    for (int i = 0; i < steps; ++i) {
      const Eigen::Vector2d p = a + (b - a) * (double(i) / steps);
      poses.push_back(poseFromXyzRpy(p.x(), p.y(), 0.0, 0.0, 0.0, yaw));
    }
  }
  return poses;
}

// Odometry with a small yaw bias per step: the classic drift a loop or walls must remove.
std::vector<Pose3> driftingOdometry(const std::vector<Pose3>& truth) {
  std::vector<Pose3> odom = {truth[0]};
  const Pose3 bias = poseFromXyzRpy(0.02, 0.0, 0.0, 0.0, 0.0, 0.01);
  for (size_t i = 1; i < truth.size(); ++i) {
    odom.push_back(odom.back() * (truth[i - 1].inverse() * truth[i]) * bias);
  }
  return odom;
}

double maxError(const FactorGraph& g, const std::vector<Pose3>& truth) {
  double worst = 0;
  for (size_t i = 0; i < truth.size(); ++i) {
    worst = std::max(worst, (g.keyframePose(i).translation() - truth[i].translation()).norm());
  }
  return worst;
}

void addOdometry(FactorGraph* g, const std::vector<Pose3>& odom) {
  for (size_t i = 0; i < odom.size(); ++i) {
    g->addKeyframe(i, odom[i]);
    if (i > 0) {
      g->addRelativePose(i - 1, i, odom[i - 1].inverse() * odom[i], Matrix6d::Identity() * 100,
                         false);
    }
  }
}

/// Both trust-region strategies remove the drift of a closed rectangle loop.
class FactorGraphTrustRegion : public ::testing::TestWithParam<TrustRegion> {};

TEST_P(FactorGraphTrustRegion, LoopClosureRemovesDrift) {
  const auto truth = rectangleLoop();
  const auto odom = driftingOdometry(truth);
  BackendConfig config;
  config.trust_region = GetParam();
  FactorGraph g{config};
  addOdometry(&g, odom);
  const double before = maxError(g, truth);
  // The robot is back at the start: the loop edge measures the true relative pose.
  const size_t last = truth.size() - 1;
  g.addRelativePose(0, last, truth[0].inverse() * truth[last], Matrix6d::Identity() * 1000, true);
  const OptimizationReport report = g.optimize();
  EXPECT_TRUE(report.usable);
  EXPECT_LT(report.final_cost, report.initial_cost);
  const double after = maxError(g, truth);
  EXPECT_GT(before, 1.0);
  EXPECT_LT(after, 0.5 * before);
}

INSTANTIATE_TEST_SUITE_P(Strategies, FactorGraphTrustRegion,
                         ::testing::Values(TrustRegion::kLevenbergMarquardt, TrustRegion::kDogleg));

TEST(FactorGraph, UnknownTrustRegionIsAConfigError) {
  BackendConfig config;
  std::vector<std::string> unknown;
  try {
    configFromJson(nlohmann::json{{"trust_region", "gauss_newton"}}, "t.yaml", &config, &unknown);
    FAIL() << "accepted gauss_newton";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              "t.yaml: trust_region: must be levenberg_marquardt or dogleg (got \"gauss_newton\")");
  }
  configFromJson(nlohmann::json{{"trust_region", "levenberg_marquardt"}}, "t.yaml", &config,
                 &unknown);
  EXPECT_EQ(config.trust_region, TrustRegion::kLevenbergMarquardt);
  EXPECT_EQ(configToJson(config).at("trust_region"), "levenberg_marquardt");
}

TEST(FactorGraph, WallObservationsCorrectHeadingDrift) {
  const auto truth = rectangleLoop();
  const auto odom = driftingOdometry(truth);
  FactorGraph g{BackendConfig()};
  addOdometry(&g, odom);
  const double before = maxError(g, truth);
  // Four walls just outside the rectangle, facing in: x = -1, x = 11, y = -1, y = 7.
  const std::vector<WallPlane> walls = {
      {0.0, 1.0}, {M_PI, 11.0}, {M_PI / 2, 1.0}, {-M_PI / 2, 7.0}};
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (uint32_t w = 0; w < walls.size(); ++w) {
    // Initialise each wall from its first observation through the drifting odometry.
    const Pose3& seen_from = odom[0];
    const Eigen::Vector3d n_b = truth[0].rotation().transpose() * walls[w].normal();
    const double d_b = walls[w].d + walls[w].normal().dot(truth[0].translation());
    const Eigen::Vector3d n_map = seen_from.rotation() * n_b;
    g.addWall(w, WallPlane::fromNormalD(n_map, d_b - n_map.dot(seen_from.translation())));
  }
  for (size_t i = 0; i < truth.size(); ++i) {
    for (uint32_t w = 0; w < walls.size(); ++w) {
      const Eigen::Vector3d n_b = truth[i].rotation().transpose() * walls[w].normal();
      const double d_b = walls[w].d + walls[w].normal().dot(truth[i].translation());
      g.addWallObservation(i, w, n_b, d_b + noise(rng));
    }
  }
  EXPECT_TRUE(g.optimize().usable);
  const double after = maxError(g, truth);
  EXPECT_LT(after, 0.2) << "before: " << before;
  EXPECT_NEAR(g.wall(1).d, 11.0, 0.1);
}

// Wall w of the rectangle (and a fifth, x = 4.5 facing -x, seen only late) as seen from `pose`.
void observeWall(FactorGraph* g, uint32_t keyframe, uint32_t w, const WallPlane& wall,
                 const Pose3& pose) {
  const Eigen::Vector3d n_b = pose.rotation().transpose() * wall.normal();
  g->addWallObservation(keyframe, w, n_b, wall.d + wall.normal().dot(pose.translation()));
}

// A window solve moves the newest keyframes and the wall only they saw; the older keyframes and
// the walls they saw stay exactly where the last full solve put them. A window as large as the
// graph is the full solve.
TEST(FactorGraph, AWindowSolveMovesOnlyTheNewestKeyframesAndTheWallsOnlyTheySaw) {
  const auto truth = rectangleLoop();
  const auto odom = driftingOdometry(truth);
  const size_t old_count = truth.size() - 6;
  const std::vector<WallPlane> walls = {
      {0.0, 1.0}, {M_PI, 11.0}, {M_PI / 2, 1.0}, {-M_PI / 2, 7.0}, {M_PI, 4.5}};
  FactorGraph g{BackendConfig()};
  addOdometry(&g, std::vector<Pose3>(odom.begin(), odom.begin() + old_count));
  for (uint32_t w = 0; w < 4; ++w) g.addWall(w, walls[w]);
  for (size_t i = 0; i < old_count; ++i) {
    for (uint32_t w = 0; w < 4; ++w) observeWall(&g, i, w, walls[w], truth[i]);
  }
  ASSERT_TRUE(g.optimize().usable);
  std::vector<Pose3> held;
  for (size_t i = 0; i < old_count; ++i) held.push_back(g.keyframePose(i));
  std::vector<WallPlane> held_walls;
  for (uint32_t w = 0; w < 4; ++w) held_walls.push_back(g.wall(w));
  // The newest keyframes start from the drifting odometry; wall 4 starts 0.3 m off.
  for (size_t i = old_count; i < truth.size(); ++i) {
    g.addKeyframe(i, g.keyframePose(i - 1) * odom[i - 1].inverse() * odom[i]);
    g.addRelativePose(i - 1, i, odom[i - 1].inverse() * odom[i], Matrix6d::Identity() * 100, false);
  }
  g.addWall(4, {M_PI, 4.8});
  for (size_t i = old_count; i < truth.size(); ++i) {
    for (uint32_t w = 0; w < 5; ++w) observeWall(&g, i, w, walls[w], truth[i]);
  }
  FactorGraph whole = g, as_large = g;
  const OptimizationReport report = g.optimize(truth.size() - old_count);
  ASSERT_TRUE(report.usable);
  EXPECT_TRUE(report.window);
  for (size_t i = 0; i < old_count; ++i) {
    EXPECT_TRUE(g.keyframePose(i).isApprox(held[i], 0.0)) << "keyframe " << i;
  }
  for (uint32_t w = 0; w < 4; ++w) {
    EXPECT_EQ(g.wall(w).d, held_walls[w].d) << "wall " << w;
    EXPECT_EQ(g.wall(w).theta, held_walls[w].theta) << "wall " << w;
  }
  EXPECT_NEAR(g.wall(4).d, 4.5, 0.05);
  for (size_t i = old_count; i < truth.size(); ++i) {
    EXPECT_LT((g.keyframePose(i).translation() - truth[i].translation()).norm(), 0.1) << i;
  }
  // A window as large as the graph is the full solve, to the bit.
  ASSERT_TRUE(whole.optimize().usable);
  const OptimizationReport large = as_large.optimize(truth.size());
  EXPECT_FALSE(large.window);
  for (size_t i = 0; i < truth.size(); ++i) {
    EXPECT_TRUE(as_large.keyframePose(i).isApprox(whole.keyframePose(i), 0.0)) << i;
  }
}

// Observations from keyframe 0 at the (fixed) origin hold the walls where they are.
void observeFromOrigin(FactorGraph* g, const std::vector<uint32_t>& walls) {
  for (uint32_t w : walls) g->addWallObservation(0, w, g->wall(w).normal(), g->wall(w).d);
}

TEST(FactorGraph, RoomCentreSettlesMidwayBetweenItsWalls) {
  FactorGraph g{BackendConfig()};
  g.addKeyframe(0, Pose3::Identity());
  g.addWall(0, {0.0, 1.0});        // x = -1
  g.addWall(1, {M_PI, 5.0});       // x = 5
  g.addWall(2, {M_PI / 2, 2.0});   // y = -2
  g.addWall(3, {-M_PI / 2, 4.0});  // y = 4
  observeFromOrigin(&g, {0, 1, 2, 3});
  g.setRoom(0, Eigen::Vector2d(0.0, 0.0), {{0, 1}, {2, 3}}, std::nullopt);
  // A corridor between walls 0 and 1, anchored along y at its free-space centre y = 10.
  g.setRoom(1, Eigen::Vector2d(0.0, 0.0), {{0, 1}}, Eigen::Vector2d(0.0, 10.0));
  EXPECT_TRUE(g.optimize().usable);
  EXPECT_NEAR(g.roomCenter(0).x(), 2.0, 1e-3);
  EXPECT_NEAR(g.roomCenter(0).y(), 1.0, 1e-3);
  EXPECT_NEAR(g.roomCenter(1).x(), 2.0, 1e-3);
  EXPECT_NEAR(g.roomCenter(1).y(), 10.0, 1e-3);
}

TEST(FactorGraph, MergingWallsMovesObservationsAndRooms) {
  FactorGraph g{BackendConfig()};
  g.addKeyframe(0, Pose3::Identity());
  g.addWall(0, {0.0, 1.0});
  g.addWall(1, {0.0, 1.2});  // the same wall, created twice
  g.addWall(2, {M_PI, 5.0});
  observeFromOrigin(&g, {0, 2});
  g.addWallObservation(0, 1, Eigen::Vector3d::UnitX(), 1.0);  // initialised 20 cm off
  g.setRoom(0, Eigen::Vector2d(0, 0), {{1, 2}}, Eigen::Vector2d(0, 0));
  g.mergeWalls(0, 1);
  EXPECT_EQ(g.wallCount(), 2u);
  EXPECT_FALSE(g.hasWall(1));
  EXPECT_TRUE(g.optimize().usable);
  EXPECT_NEAR(g.wall(0).d, 1.0, 1e-3);
  EXPECT_NEAR(g.roomCenter(0).x(), 2.0, 1e-2);
}

TEST(FactorGraph, WallToWallEdgePullsDuplicatesTogether) {
  FactorGraph g{BackendConfig()};
  g.addKeyframe(0, Pose3::Identity());
  g.addWall(0, {0.0, 1.0});
  g.addWall(1, {0.05, 1.3});
  g.addWallObservation(0, 0, Eigen::Vector3d::UnitX(), 1.0);
  g.addWallToWall(0, 1);
  EXPECT_TRUE(g.optimize().usable);
  EXPECT_NEAR(g.wall(1).theta, 0.0, 1e-3);
  EXPECT_NEAR(g.wall(1).d, 1.0, 1e-3);
}

// The first scan was taken on a 0.5 deg roll and pitch tilt (the robot rocked); every later
// keyframe stands level on the floor. The map is that first keyframe's frame, so with its
// orientation held the vertical walls and the odometry disagree and the path climbs; with a soft
// tilt prior the walls level the map.
double climbAlongLevelPath(double anchor_tilt_sigma) {
  const double tilt = 0.5 * M_PI / 180.0;
  std::vector<Pose3> truth = {poseFromXyzRpy(0.0, 0.0, 0.0, tilt, tilt, 0.0)};
  for (int i = 1; i < 10; ++i) truth.push_back(poseFromXyzRpy(i, 0.0, 0.0, 0.0, 0.0, 0.0));
  BackendConfig config;
  config.anchor_tilt_sigma = anchor_tilt_sigma;
  FactorGraph g{config};
  const std::vector<WallPlane> walls = {{M_PI / 2, 2.0}, {-M_PI / 2, 2.0}, {M_PI, 12.0}};
  for (uint32_t w = 0; w < walls.size(); ++w) g.addWall(w, walls[w]);
  for (size_t i = 0; i < truth.size(); ++i) {
    g.addKeyframe(i, truth[0].inverse() * truth[i]);  // the odometry starts at identity
    if (i > 0) {
      g.addRelativePose(i - 1, i, truth[i - 1].inverse() * truth[i], Matrix6d::Identity() * 1e4,
                        false);
    }
    for (uint32_t w = 0; w < walls.size(); ++w) {
      const Eigen::Vector3d n_b = truth[i].rotation().transpose() * walls[w].normal();
      g.addWallObservation(i, w, n_b, walls[w].d + walls[w].normal().dot(truth[i].translation()));
    }
  }
  EXPECT_TRUE(g.optimize().usable);
  return std::abs(g.keyframePose(9).translation().z() - g.keyframePose(1).translation().z());
}

TEST(FactorGraph, VerticalWallsLevelAMapAnchoredOnATiltedFirstScan) {
  const double held = climbAlongLevelPath(0.0);  // 8 m at up to 0.7 deg
  const double levelled = climbAlongLevelPath(BackendConfig().anchor_tilt_sigma);
  EXPECT_GT(held, 0.03);
  // Thirty wall observations against a 3 deg prior: the walls win almost all of the tilt.
  EXPECT_LT(levelled, 0.2 * held);
}

TEST(FactorGraph, RejectsBadInput) {
  FactorGraph g{BackendConfig()};
  g.addKeyframe(0, Pose3::Identity());
  EXPECT_THROW(g.addRelativePose(0, 1, Pose3::Identity(), Matrix6d::Identity(), false),
               std::invalid_argument);
  g.addKeyframe(1, Pose3::Identity());
  EXPECT_THROW(g.addRelativePose(0, 1, Pose3::Identity(), -Matrix6d::Identity(), false),
               std::invalid_argument);
  EXPECT_THROW(WallPlane::fromNormalD(Eigen::Vector3d::UnitZ(), 1.0), std::invalid_argument);
  BackendConfig bad;
  bad.room_sigma = 0;
  EXPECT_THROW(FactorGraph{bad}, ConfigError);
  bad = BackendConfig();
  bad.anchor_tilt_sigma = -0.1;
  EXPECT_THROW(FactorGraph{bad}, ConfigError);
}

}  // namespace
}  // namespace tacs
