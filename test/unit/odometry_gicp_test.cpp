#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>

#include <Eigen/Eigenvalues>
#include <fstream>

#include "common/box_room.h"
#include "common/test_paths.h"
#include "tacs_graphs/odometry/gicp.h"
#include "tacs_graphs/odometry/preprocess.h"

namespace tacs {
namespace {

using test::rotationErrorDeg;
using test::translationError;

PointCloud preprocessed(const PointCloud& raw) { return preprocess(raw, PreprocessConfig()); }

TEST(PlaneRegularizedCovariance, IsThinAlongTheNormal) {
  std::vector<Eigen::Vector3d> points;
  std::vector<uint32_t> all;
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) {
      points.emplace_back(0.1 * i, 0.07 * j, 2.0 + 0.001 * ((i * 7 + j) % 3));
      all.push_back(static_cast<uint32_t>(points.size() - 1));
    }
  }
  const Eigen::Matrix3d cov = planeRegularizedCovariance(points, all);
  EXPECT_NEAR(cov(2, 2), 1e-3, 1e-4);
  EXPECT_NEAR(cov(0, 0), 1.0, 1e-3);
  EXPECT_NEAR(cov(1, 1), 1.0, 1e-3);
  EXPECT_TRUE(planeRegularizedCovariance(points, {0, 1}).isIdentity());
}

TEST(Gicp, RecoversAKnownMotionInASyntheticRoom) {
  const test::BoxRoom room;
  const Pose3 T_world_target = poseFromXyzRpy(4.0, 3.0, 0.5, 0.0, 0.0, 0.3);
  const Pose3 T_world_source = poseFromXyzRpy(4.4, 3.2, 0.52, 0.02, -0.01, 0.45);
  const Pose3 truth = T_world_target.inverse() * T_world_source;
  Gicp gicp;
  gicp.setTarget(preprocessed(test::renderScan(room, T_world_target, 1)));
  gicp.setSource(preprocessed(test::renderScan(room, T_world_source, 2)));
  const GicpResult r = gicp.align(Pose3::Identity());
  EXPECT_TRUE(r.converged);
  EXPECT_LT(translationError(r.T_target_source, truth), 0.03);
  EXPECT_LT(rotationErrorDeg(r.T_target_source, truth), 0.3);
  EXPECT_GT(r.inlier_ratio, 0.8);
  EXPECT_LT(r.fitness, 0.2 * 0.2);  // pairs of 0.2 m voxel centroids on the same surfaces
  // The information is symmetric positive definite in a fully constrained room.
  EXPECT_TRUE(r.information.isApprox(r.information.transpose()));
  using Solver = Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>>;
  EXPECT_GT(Solver(r.information).eigenvalues().minCoeff(), 0.0);
}

TEST(Gicp, ReusesOnePreparedTargetForManySources) {
  const test::BoxRoom room;
  const Pose3 T_world_target = poseFromXyzRpy(5.0, 3.5, 0.5, 0.0, 0.0, 0.0);
  Gicp gicp;
  gicp.setTarget(preprocessed(test::renderScan(room, T_world_target, 3)));
  const GicpCloud* target = gicp.target().get();
  for (int k = 0; k < 3; ++k) {
    const Pose3 T_world_source = poseFromXyzRpy(5.0 - 0.3 * k, 3.5 + 0.2 * k, 0.5, 0, 0, -0.1 * k);
    gicp.setSource(preprocessed(test::renderScan(room, T_world_source, 10 + k)));
    const Pose3 truth = T_world_target.inverse() * T_world_source;
    const GicpResult r = gicp.align(Pose3::Identity());
    EXPECT_LT(translationError(r.T_target_source, truth), 0.03) << "source " << k;
    EXPECT_LT(rotationErrorDeg(r.T_target_source, truth), 0.3) << "source " << k;
  }
  EXPECT_EQ(gicp.target().get(), target);
}

TEST(Gicp, EvaluateScoresTheTruthBetterThanAWrongPose) {
  const test::BoxRoom room;
  const Pose3 T_world_target = poseFromXyzRpy(4.0, 3.0, 0.5, 0, 0, 0);
  const Pose3 T_world_source = poseFromXyzRpy(4.5, 3.0, 0.5, 0, 0, 0.2);
  Gicp gicp;
  gicp.setTarget(preprocessed(test::renderScan(room, T_world_target, 4)));
  gicp.setSource(preprocessed(test::renderScan(room, T_world_source, 5)));
  const GicpResult good = gicp.evaluate(T_world_target.inverse() * T_world_source);
  const GicpResult bad = gicp.evaluate(poseFromXyzRpy(0, 1.5, 0, 0, 0, 1.0));
  EXPECT_GT(good.inlier_ratio, 0.8);
  EXPECT_LT(good.fitness, bad.fitness);
  EXPECT_GT(good.inlier_ratio, bad.inlier_ratio);
}

TEST(Gicp, WithoutDataReturnsNotConvergedAndTheGuess) {
  Gicp gicp;
  const Pose3 guess = poseFromXyzRpy(1, 2, 3, 0, 0, 0.5);
  GicpResult r = gicp.align(guess);
  EXPECT_FALSE(r.converged);
  EXPECT_TRUE(r.T_target_source.isApprox(guess));
  gicp.setTarget(PointCloud());
  gicp.setSource(PointCloud());
  r = gicp.align(guess);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.inliers, 0u);
}

Pose3 readMatrix4(const std::string& path) {
  std::ifstream in(path);
  Eigen::Matrix4d m;
  for (int i = 0; i < 16; ++i) in >> m(i / 4, i % 4);
  EXPECT_TRUE(in.good() || in.eof()) << "cannot read " << path;
  return Pose3(m);
}

TEST(Gicp, AlignsTheRealHdl32ScanPair) {
  const std::string dir = test::sharedDataDir() + "/hdl32_scan_pair/";
  PointCloud target_raw, source_raw;
  ASSERT_EQ(pcl::io::loadPCDFile(dir + "251370668.pcd", target_raw), 0);
  ASSERT_EQ(pcl::io::loadPCDFile(dir + "251371071.pcd", source_raw), 0);
  const Pose3 truth = readMatrix4(dir + "relative.txt");
  PreprocessStats stats;
  Gicp gicp;
  gicp.setTarget(preprocess(target_raw, PreprocessConfig(), &stats));
  EXPECT_GT(stats.out_of_range, 4000u);  // the (0,0,0) returns
  gicp.setSource(preprocess(source_raw, PreprocessConfig()));
  const GicpResult r = gicp.align(Pose3::Identity());
  EXPECT_TRUE(r.converged);
  EXPECT_LT(translationError(r.T_target_source, truth), 0.05);
  EXPECT_LT(rotationErrorDeg(r.T_target_source, truth), 0.5);
}

}  // namespace
}  // namespace tacs
