#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>

#include <Eigen/Eigenvalues>
#include <fstream>
#include <random>

#include "common/box_room.h"
#include "common/real_data.h"
#include "tacs_graphs/odometry/deskew.h"
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

// The closed form (one normal) against the full eigendecomposition it replaces, on tilted noisy
// patches and on a degenerate line, where the normal is not unique.
TEST(PlaneRegularizedCovariance, MatchesTheFullEigendecomposition) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.01);
  const auto reference = [](const std::vector<Eigen::Vector3d>& pts) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& p : pts) mean += p / pts.size();
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& p : pts) cov += (p - mean) * (p - mean).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    return Eigen::Matrix3d(eig.eigenvectors() * Eigen::Vector3d(1e-3, 1.0, 1.0).asDiagonal() *
                           eig.eigenvectors().transpose());
  };
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(0.1 * trial, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).matrix();
    std::vector<Eigen::Vector3d> points;
    std::vector<uint32_t> all;
    for (int i = 0; i < 10; ++i) {
      points.push_back(R * Eigen::Vector3d(0.1 * (i % 4), 0.13 * (i / 4), noise(rng)) +
                       Eigen::Vector3d(5.0, -3.0, 1.0));
      all.push_back(static_cast<uint32_t>(i));
    }
    EXPECT_TRUE(planeRegularizedCovariance(points, all).isApprox(reference(points), 1e-6))
        << "trial " << trial;
  }
  std::vector<Eigen::Vector3d> line;
  for (int i = 0; i < 10; ++i) line.emplace_back(0.1 * i, 0.2 * i, 1.0);
  const Eigen::Matrix3d cov = planeRegularizedCovariance(line, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
  // Any normal orthogonal to the line will do; the line direction keeps variance 1.
  const Eigen::Vector3d along = Eigen::Vector3d(1.0, 2.0, 0.0).normalized();
  EXPECT_NEAR(along.dot(cov * along), 1.0, 1e-9);
  EXPECT_TRUE(cov.isApprox(cov.transpose()));
}

// A hint (right, wrong, out of range) never changes the answer of the nearest-point search.
TEST(GicpCloud, NearestWithAHintIsTheExactNearest) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coord(-5.0, 5.0);
  std::vector<Eigen::Vector3d> points(2000);
  for (auto& p : points) p = Eigen::Vector3d(coord(rng), coord(rng), coord(rng));
  const GicpCloud::ConstPtr cloud = GicpCloud::build(points, 10, 1);
  for (int q = 0; q < 500; ++q) {
    const Eigen::Vector3d query(coord(rng), coord(rng), coord(rng));
    double plain_sq = 0.0;
    const int64_t plain = cloud->nearest(query, 1.0, &plain_sq);
    for (int64_t hint : {plain, int64_t{q}, int64_t{-1}, int64_t{5000}}) {
      double hinted_sq = 0.0;
      EXPECT_EQ(cloud->nearest(query, 1.0, &hinted_sq, hint), plain) << "hint " << hint;
      if (plain >= 0) {
        EXPECT_FLOAT_EQ(hinted_sq, plain_sq);
      }
    }
  }
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

// The local map merged from keyframe clouds with their own covariances (no neighbour search):
// one point per voxel at its members' centroid, discs that follow the surfaces, and a target a
// third scan aligns to as well as to the map whose covariances were searched anew.
TEST(MergeGicpClouds, VoxelCentroidsCarryTheKeyframesPlanes) {
  const test::BoxRoom room;
  const Pose3 T_a = poseFromXyzRpy(4.0, 3.0, 0.5, 0.0, 0.0, 0.3);
  const Pose3 T_b = poseFromXyzRpy(4.6, 3.3, 0.5, 0.0, 0.0, 0.7);
  const auto a = GicpCloud::build(preprocessed(test::renderScan(room, T_a, 1)), 10, 1);
  const auto b = GicpCloud::build(preprocessed(test::renderScan(room, T_b, 2)), 10, 1);
  const GicpCloud::ConstPtr merged = mergeGicpClouds({{T_a, a}, {T_b, b}}, 0.2, 2);
  EXPECT_LT(merged->size(), a->size() + b->size());  // the views overlap: shared voxels
  EXPECT_GT(merged->size(), std::max(a->size(), b->size()));
  // Each point is the centroid of its voxel's members: inside that voxel.
  for (const Eigen::Vector3d& p : merged->points()) {
    const Eigen::Vector3d cell = (p / 0.2).array().floor();
    EXPECT_TRUE(((p / 0.2) - cell).minCoeff() >= 0.0);
  }
  // Points on the floor (z about 0 in the world) a metre or more from the walls keep a vertical
  // normal, but for some where a scan's neighbours lay along one sparse ring (no plane): the
  // reason the map's covariances are searched anew for sparse LiDARs (local_map_covariances).
  size_t floor = 0, vertical = 0;
  for (size_t i = 0; i < merged->size(); ++i) {
    const Eigen::Vector3d& p = merged->points()[i];
    if (std::abs(p.z()) > 0.05 || p.x() < 1.0 || p.x() > 9.0 || p.y() < 1.0 || p.y() > 6.0) {
      continue;
    }
    ++floor;
    const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
    vertical += up.dot(merged->covariances()[i] * up) < 0.05;
  }
  EXPECT_GT(floor, 20u);
  EXPECT_GE(vertical, 0.8 * floor) << vertical << " of " << floor;
  // Same result as on the neighbour-searched map of the same points, within a few millimetres.
  const Pose3 T_c = poseFromXyzRpy(4.3, 3.1, 0.52, 0.01, 0.0, 0.5);
  const auto c = GicpCloud::build(preprocessed(test::renderScan(room, T_c, 3)), 10, 1);
  Gicp gicp;
  gicp.setSource(c);
  gicp.setTarget(merged);
  const GicpResult carried = gicp.align(T_c * Pose3(Eigen::Translation3d(0.1, -0.1, 0.0)));
  EXPECT_LT(translationError(carried.T_target_source, T_c), 0.03);
  EXPECT_LT(rotationErrorDeg(carried.T_target_source, T_c), 0.3);
  gicp.setTarget(GicpCloud::build(merged->points(), 10, 1));
  const GicpResult searched = gicp.align(T_c * Pose3(Eigen::Translation3d(0.1, -0.1, 0.0)));
  EXPECT_LT(translationError(carried.T_target_source, searched.T_target_source), 0.01);
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

TEST(Gicp, InlierRatioIsEvaluatesWithoutTheHessian) {
  const test::BoxRoom room;
  const Pose3 T_world_target = poseFromXyzRpy(4.0, 3.0, 0.5, 0, 0, 0);
  const Pose3 T_world_source = poseFromXyzRpy(4.5, 3.0, 0.5, 0, 0, 0.2);
  GicpConfig config;
  config.max_correspondence_distance_m = 0.3;  // the odometry's fit test gate
  Gicp gicp(config);
  gicp.setTarget(preprocessed(test::renderScan(room, T_world_target, 4)));
  gicp.setSource(preprocessed(test::renderScan(room, T_world_source, 5)));
  const Pose3 truth = T_world_target.inverse() * T_world_source;
  for (const Pose3& T : {truth, poseFromXyzRpy(0.2, 0.1, 0, 0, 0, 0.3), Pose3::Identity()}) {
    EXPECT_EQ(gicp.inlierRatio(T), gicp.evaluate(T).inlier_ratio);
  }
  EXPECT_GT(gicp.inlierRatio(truth), 0.8);
  EXPECT_LT(gicp.inlierRatio(poseFromXyzRpy(0, 1.5, 0, 0, 0, 1.0)), gicp.inlierRatio(truth));
  EXPECT_EQ(Gicp(config).inlierRatio(truth), 0.0);  // no clouds
}

// The source sees a cabinet 0.3 m in front of a wall that the target does not hold (as a scan
// sees a surface its local map lacks, e.g. through a doorway). Its face pairs with the wall behind
// within the gate; least squares gives those pairs a weight that drags the pose toward the wall,
// the robust kernel leaves them out.
TEST(Gicp, RobustKernelIsNotDraggedByStructureOnlyTheSourceHolds) {
  test::BoxRoom empty, furnished;
  empty.obstacles.clear();
  furnished.obstacles = {{{2.0, 6.7, 0.0}, {6.0, 7.0, 2.0}}};  // a 4 m cabinet at the y = 7 wall
  const Pose3 T_world_target = poseFromXyzRpy(5.0, 3.5, 0.5, 0.0, 0.0, 0.0);
  const Pose3 T_world_source = poseFromXyzRpy(5.3, 3.6, 0.5, 0.0, 0.0, 0.05);
  const Pose3 truth = T_world_target.inverse() * T_world_source;
  const PointCloud target = preprocessed(test::renderScan(empty, T_world_target, 1));
  const PointCloud source = preprocessed(test::renderScan(furnished, T_world_source, 2));
  const auto align = [&](double robust_m) {
    GicpConfig config;
    config.robust_plane_distance_m = robust_m;
    Gicp gicp(config);
    gicp.setTarget(target);
    gicp.setSource(source);
    return gicp.align(Pose3::Identity());
  };
  const GicpResult plain = align(0.0);
  const GicpResult robust = align(0.05);
  EXPECT_GT(translationError(plain.T_target_source, truth), 0.02);
  EXPECT_LT(translationError(robust.T_target_source, truth), 0.005);
  EXPECT_LT(rotationErrorDeg(robust.T_target_source, truth), 0.1);
  EXPECT_TRUE(robust.converged);
}

// A sweep measured while the sensor turns at 90 deg/s and drives at 1.5 m/s (a point measured t s
// into the sweep, seen from the pose the sensor had then), registered without deskew: rigid, the
// pose is off by the motion within the sweep; with the point times, the registration finds the
// sweep's pose and its velocity (GicpResult::sweep_velocity).
TEST(Gicp, WithPointTimesTheSweepsOwnMotionIsEstimated) {
  const test::BoxRoom room;
  const Pose3 T_world_target = poseFromXyzRpy(4.0, 3.0, 0.5, 0.0, 0.0, 0.0);
  const Pose3 T_world_source = poseFromXyzRpy(4.3, 3.2, 0.5, 0.0, 0.0, 0.2);
  BodyVelocity velocity;
  velocity.linear = Eigen::Vector3d(1.5, 0.0, 0.0);
  velocity.angular = Eigen::Vector3d(0.0, 0.0, 90.0 * M_PI / 180.0);
  const PointCloud still = test::renderScan(room, T_world_source, 3);
  PointCloud moving = still;
  std::vector<float> times(still.size());
  for (size_t i = 0; i < still.size(); ++i) {
    // The head turns once in 0.1 s; the point's azimuth gives its time.
    const auto& p = still.points[i];
    const double azimuth = std::atan2(p.y, p.x);
    times[i] =
        static_cast<float>(0.1 * (azimuth < 0.0 ? azimuth + 2.0 * M_PI : azimuth) / (2.0 * M_PI));
    moving.points[i].getVector3fMap() =
        (motionOver(velocity, times[i]).inverse() * p.getVector3fMap().cast<double>())
            .cast<float>();
  }
  std::vector<float> kept_times;
  const PointCloud source = preprocess(moving, PreprocessConfig(), nullptr, &times, &kept_times);
  ASSERT_EQ(kept_times.size(), source.size());
  const Pose3 truth = T_world_target.inverse() * T_world_source;
  Gicp gicp;
  gicp.setTarget(preprocessed(test::renderScan(room, T_world_target, 1)));
  gicp.setSource(source);
  const GicpResult rigid = gicp.align(Pose3::Identity());
  gicp.setSourceTimes({kept_times.begin(), kept_times.end()});
  const GicpResult timed = gicp.align(Pose3::Identity());
  EXPECT_GT(translationError(rigid.T_target_source, truth), 0.03);
  EXPECT_LT(translationError(timed.T_target_source, truth), 0.01);
  EXPECT_LT(rotationErrorDeg(timed.T_target_source, truth), 0.3);  // as a still scan's
  EXPECT_NEAR(timed.sweep_velocity[0], 1.5, 0.1);
  EXPECT_NEAR(timed.sweep_velocity[5] * 180.0 / M_PI, 90.0, 3.0);
  EXPECT_LT(timed.sweep_velocity.segment<4>(1).norm(), 0.1);
  EXPECT_TRUE(rigid.sweep_velocity.isZero());
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
  TACS_DATA_SET_OR_SKIP(dir, "hdl32_scan_pair");
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

// parallel.h promises results bit-identical for any thread count: the covariances (parallelFor)
// and the Gauss-Newton sums (parallelReduce) of a real scan pair at 1, 2 and 3 threads.
TEST(Gicp, ResultsAreBitIdenticalForAnyThreadCount) {
  TACS_DATA_SET_OR_SKIP(dir, "hdl32_scan_pair");
  PointCloud target_raw, source_raw;
  ASSERT_EQ(pcl::io::loadPCDFile(dir + "251370668.pcd", target_raw), 0);
  ASSERT_EQ(pcl::io::loadPCDFile(dir + "251371071.pcd", source_raw), 0);
  const PointCloud target = preprocess(target_raw, PreprocessConfig());
  const PointCloud source = preprocess(source_raw, PreprocessConfig());
  const auto run = [&](int threads) {
    GicpConfig config;
    config.num_threads = threads;
    Gicp gicp(config);
    gicp.setTarget(target);
    gicp.setSource(source);
    return std::make_pair(gicp.align(Pose3::Identity()), gicp.target()->covariances());
  };
  const auto [one, one_covariances] = run(1);
  ASSERT_TRUE(one.converged);
  for (int threads : {2, 3}) {
    const auto [many, many_covariances] = run(threads);
    EXPECT_EQ(many.iterations, one.iterations) << threads;
    EXPECT_TRUE(many.T_target_source.matrix() == one.T_target_source.matrix()) << threads;
    EXPECT_TRUE(many.information == one.information) << threads;
    EXPECT_EQ(many.fitness, one.fitness) << threads;
    ASSERT_EQ(many_covariances.size(), one_covariances.size());
    for (size_t i = 0; i < one_covariances.size(); ++i) {
      ASSERT_TRUE(many_covariances[i] == one_covariances[i]) << "point " << i << ", " << threads;
    }
  }
}

}  // namespace
}  // namespace tacs
