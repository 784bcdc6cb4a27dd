#include <gtest/gtest.h>

#include <random>

#include "tacs_graphs/eval/trajectory_metrics.h"

namespace tacs {
namespace {

Trajectory circle(double radius, int n, double dt) {
  Trajectory t;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    t.push_back({100.0 + i * dt, poseFromXyzRpy(radius * std::cos(a), radius * std::sin(a),
                                                0.1 * std::sin(3 * a), 0, 0, a + M_PI / 2)});
  }
  return t;
}

TEST(TrajectoryMetrics, AteIsZeroForARigidlyMovedCopy) {
  const Trajectory gt = circle(5.0, 100, 0.1);
  Trajectory est = gt;
  const Pose3 offset = poseFromXyzRpy(3, -2, 1, 0.1, 0.2, 1.0);
  for (auto& p : est) p.pose = offset * p.pose;
  const AteResult r = computeAte(est, gt);
  EXPECT_EQ(r.pairs, 100u);
  EXPECT_LT(r.rmse, 1e-9);
  EXPECT_TRUE((r.T_gt_estimate * offset).isApprox(Pose3::Identity(), 1e-9));
}

TEST(TrajectoryMetrics, AteMeasuresKnownNoise) {
  const Trajectory gt = circle(5.0, 2000, 0.1);
  Trajectory est = gt;
  std::mt19937 rng(1);
  std::normal_distribution<double> n(0.0, 0.1);
  for (auto& p : est) p.pose.translation() += Eigen::Vector3d(n(rng), n(rng), n(rng));
  // The RMSE of isotropic 3D noise of sigma 0.1 is sqrt(3) * 0.1.
  EXPECT_NEAR(computeAte(est, gt).rmse, std::sqrt(3.0) * 0.1, 0.01);
}

TEST(TrajectoryMetrics, AssociationPicksNearestStampWithinTolerance) {
  Trajectory gt = {{1.0, Pose3::Identity()},
                   {1.1, Pose3::Identity()},
                   {1.1, Pose3::Identity()},
                   {1.2, Pose3::Identity()}};
  Trajectory est = {{1.04, Pose3::Identity()}, {1.19, Pose3::Identity()}, {5.0, Pose3::Identity()}};
  const auto pairs = associateByTime(est, gt, 0.05);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[0].second, 0u);
  EXPECT_EQ(pairs[1].second, 3u);
  EXPECT_THROW(computeAte(est, gt, 0.05), std::invalid_argument);
}

TEST(TrajectoryMetrics, DriftOfAScaleErrorIsItsShare) {
  // Straight line, estimate 2% too long: 0.2 m error per 10 m.
  Trajectory gt, est;
  for (int i = 0; i <= 300; ++i) {
    gt.push_back({i * 0.1, poseFromXyzRpy(0.1 * i, 0, 0, 0, 0, 0)});
    est.push_back({i * 0.1, poseFromXyzRpy(0.102 * i, 0, 0, 0, 0, 0)});
  }
  const DriftResult d = computeDrift(est, gt, 10.0);
  EXPECT_GT(d.segments, 100u);
  EXPECT_NEAR(d.mean_error_m, 0.2, 0.01);
  EXPECT_NEAR(d.percent, 2.0, 0.1);
  EXPECT_NEAR(pathLength(gt), 30.0, 1e-9);
}

}  // namespace
}  // namespace tacs
