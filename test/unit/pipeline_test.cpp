#include <gtest/gtest.h>
#include <pcl/common/transforms.h>

#include <filesystem>
#include <limits>
#include <thread>

#include "common/test_paths.h"
#include "tacs_graphs/common/bounded_queue.h"
#include "tacs_graphs/common/trajectory_io.h"
#include "tacs_graphs/eval/trajectory_metrics.h"
#include "tacs_graphs/pipeline/run_folder.h"
#include "tacs_graphs/sim/scan_stream.h"

namespace tacs {
namespace {

/// Streams the first `seconds` of the smoke world through a pipeline.
struct SmokeRun {
  explicit SmokeRun(double seconds, const PipelineConfig& config = {}) : pipeline(config) {
    sim::SimOptions options;
    options.duration_s = seconds;
    sim::ScanStream stream(sim::loadWorld(test::sourceDir() + "/worlds/smoke.json"), options);
    const Eigen::Affine3f T_base_sensor = stream.baseToSensor().cast<float>();
    sim::SimScan scan;
    while (stream.next(&scan)) {
      PointCloud in_base;
      pcl::transformPointCloud(sim::toPointCloud(scan), in_base, T_base_sensor);
      pipeline.processScan(scan.stamp, in_base);
    }
    pipeline.finish();
    ground_truth = stream.groundTruth();
  }
  Pipeline pipeline;
  Trajectory ground_truth;
};

TEST(Pipeline, TracksTheSmokeWorldAndMapsItsWalls) {
  SmokeRun run(8.0);
  const PipelineStats& stats = run.pipeline.stats();
  EXPECT_EQ(stats.rejected_scans, 0u) << stats.first_rejection;
  EXPECT_GT(stats.keyframes, 10u);
  EXPECT_EQ(run.pipeline.odometryTrajectory().size(), stats.scans);
  const AteResult ate = computeAte(run.pipeline.keyframeTrajectory(), run.ground_truth);
  EXPECT_LT(ate.rmse, 0.10);
  // In 8 s the robot sees room A, the door to room B and the corridor: at most the 14 wall faces of
  // the world plus the sides of its two tall boxes, and surely the four faces around room A.
  const size_t walls = run.pipeline.sceneGraph().walls.size();
  EXPECT_GE(walls, 4u);
  EXPECT_LE(walls, 22u);
  EXPECT_GT(run.pipeline.backend().optimizations(), 0);
}

TEST(Pipeline, OdometryRunningAheadOnAnotherThreadGivesTheSameRun) {
  // tacs_offline's way: odometryOf on a thread of its own, takeOdometry in scan order here.
  SmokeRun sequential(6.0);
  Pipeline pipeline{PipelineConfig{}};
  sim::SimOptions options;
  options.duration_s = 6.0;
  sim::ScanStream stream(sim::loadWorld(test::sourceDir() + "/worlds/smoke.json"), options);
  const Eigen::Affine3f T_base_sensor = stream.baseToSensor().cast<float>();
  BoundedQueue<ScanOdometry> queue(4);
  std::thread odometry_thread([&] {
    sim::SimScan scan;
    while (stream.next(&scan)) {
      PointCloud in_base;
      pcl::transformPointCloud(sim::toPointCloud(scan), in_base, T_base_sensor);
      if (!queue.push(pipeline.odometryOf(scan.stamp, in_base))) break;
    }
    queue.close();
  });
  while (const auto scan = queue.pop()) pipeline.takeOdometry(*scan);
  odometry_thread.join();
  pipeline.finish();

  EXPECT_EQ(pipeline.stats().keyframes, sequential.pipeline.stats().keyframes);
  const Trajectory a = sequential.pipeline.keyframeTrajectory();
  const Trajectory b = pipeline.keyframeTrajectory();
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 5u);
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].stamp, b[i].stamp);
    EXPECT_TRUE(a[i].pose.matrix() == b[i].pose.matrix()) << "keyframe " << i;
  }
  EXPECT_EQ(pipeline.sceneGraph().walls.size(), sequential.pipeline.sceneGraph().walls.size());
}

TEST(Pipeline, OdometryAndWallsOnlyWhenRoomsAndLoopsAreOff) {
  PipelineConfig config;
  config.rooms.method = RoomMethod::kNone;
  config.loop_closure.method = LoopMethod::kNone;
  SmokeRun run(8.0, config);
  EXPECT_GT(run.pipeline.stats().keyframes, 10u);
  EXPECT_GE(run.pipeline.sceneGraph().walls.size(), 4u);
  EXPECT_TRUE(run.pipeline.sceneGraph().rooms.empty());
  EXPECT_TRUE(run.pipeline.sceneGraph().loops.empty());
  EXPECT_LT(computeAte(run.pipeline.keyframeTrajectory(), run.ground_truth).rmse, 0.10);
}

TEST(Pipeline, GivenPosesReplaceTheOdometryAndScansOutsideThemAreCounted) {
  sim::SimOptions options;
  options.duration_s = 4.0;
  sim::ScanStream stream(sim::loadWorld(test::sourceDir() + "/worlds/smoke.json"), options);
  // Given poses cover only the middle of the run: the first and last scans have none.
  Trajectory given;
  for (const StampedPose& p : stream.groundTruth()) {
    if (p.stamp > 1001.0 && p.stamp < 1003.0) given.push_back(p);
  }
  ASSERT_GT(given.size(), 10u);
  Pipeline pipeline{PipelineConfig{}};
  pipeline.useGivenPoses(given);
  const Eigen::Affine3f T_base_sensor = stream.baseToSensor().cast<float>();
  sim::SimScan scan;
  size_t scans = 0;
  while (stream.next(&scan)) {
    PointCloud in_base;
    pcl::transformPointCloud(sim::toPointCloud(scan), in_base, T_base_sensor);
    pipeline.processScan(scan.stamp, in_base);
    ++scans;
  }
  const PipelineStats& stats = pipeline.stats();
  EXPECT_EQ(stats.scans, scans);
  EXPECT_EQ(stats.scans_outside_poses, scans - given.size());
  ASSERT_EQ(pipeline.odometryTrajectory().size(), given.size());
  for (size_t i = 0; i < given.size(); ++i) {
    EXPECT_TRUE(pipeline.odometryTrajectory()[i].pose.isApprox(given[i].pose, 1e-9));
  }
}

TEST(Pipeline, RejectsBadScansAndKeepsGoing) {
  Pipeline pipeline{PipelineConfig{}};
  PointCloud empty;
  ScanOutcome outcome = pipeline.processScan(1.0, empty);
  EXPECT_FALSE(outcome.accepted);
  EXPECT_FALSE(outcome.error.empty());
  PointCloud nans;
  for (int i = 0; i < 500; ++i) {
    pcl::PointXYZI p;
    p.x = p.y = p.z = std::numeric_limits<float>::quiet_NaN();
    nans.push_back(p);
  }
  outcome = pipeline.processScan(1.1, nans);
  EXPECT_FALSE(outcome.accepted);
  EXPECT_EQ(pipeline.stats().rejected_scans, 2u);
  EXPECT_EQ(pipeline.stats().keyframes, 0u);
  pipeline.finish();  // nothing to optimise, no throw
  EXPECT_TRUE(pipeline.sceneGraph().keyframes.empty());
}

TEST(RunFolder, WritesEveryFileOfTheContract) {
  SmokeRun run(3.0);
  const std::string dir = ::testing::TempDir() + "/tacs_run_folder_test";
  std::filesystem::remove_all(dir);
  writeRunFolder(dir, run.pipeline, {"smoke", 1.5});
  for (const char* name : {"trajectory_tum.txt", "odometry_tum.txt", "scene_graph.json",
                           "timing.json", "config.json", "map.pcd", "map.bt", "topdown.png"}) {
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + name)) << name;
  }
  const SceneGraph loaded = SceneGraph::load(dir + "/scene_graph.json");
  EXPECT_EQ(loaded.keyframes.size(), run.pipeline.stats().keyframes);
  EXPECT_EQ(readTum(dir + "/trajectory_tum.txt").size(), run.pipeline.stats().keyframes);
  EXPECT_EQ(readTum(dir + "/odometry_tum.txt").size(), run.pipeline.stats().scans);
  const nlohmann::json timing = timingJson(run.pipeline, {"smoke", 1.5});
  EXPECT_EQ(timing["scans"].get<size_t>(), run.pipeline.stats().scans);
  EXPECT_TRUE(timing["stages_ms"].contains("odometry"));
  EXPECT_TRUE(timing.contains("t_fgo_s"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tacs
