#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "tacs_graphs/odometry/deskew.h"
#include "tacs_graphs/odometry/point_times.h"

namespace tacs {
namespace {

constexpr double kStamp = 1630577758.5;  // a unix time, as drivers stamp scans
constexpr int kPoints = 2000;

// One 0.1 s sweep: point i measured at i / kPoints * 0.1 s after its first point, written in
// `unit_s` seconds per unit, counting from `origin_s` (absolute seconds).
std::vector<double> sweep(double unit_s, double origin_s, double first_point_s = kStamp) {
  std::vector<double> raw(kPoints);
  for (int i = 0; i < kPoints; ++i) {
    const double t = first_point_s + 0.1 * i / kPoints;
    raw[i] = (t - origin_s) / unit_s;
  }
  return raw;
}

// Expects offsets from the stamp running 0 .. 0.1 s along the sweep (plus `shift`).
void expectSweepOffsets(const PointTimes& times, double shift = 0.0) {
  ASSERT_TRUE(times.ok) << times.message;
  ASSERT_EQ(times.offset_s.size(), static_cast<size_t>(kPoints));
  EXPECT_NEAR(times.offset_s.front(), shift, 1e-6);
  EXPECT_NEAR(times.offset_s.back(), shift + 0.1 * (kPoints - 1) / kPoints, 1e-6);
  EXPECT_NEAR(times.span_s, 0.1 * (kPoints - 1) / kPoints, 1e-6);
}

TEST(PointTimes, VelodyneFloatSecondsFromTheStamp) {
  const PointTimes t = resolvePointTimes("time", sweep(1.0, kStamp), kStamp, PointTimeConfig());
  expectSweepOffsets(t);
  EXPECT_EQ(t.unit, "s");
  EXPECT_FALSE(t.absolute);
}

TEST(PointTimes, VelodyneStampedAtTheLastPointHasNegativeTimes) {
  // Some Velodyne drivers stamp the scan with its last packet: times run up to zero.
  const double last = kStamp + 0.1 * (kPoints - 1) / kPoints;
  const PointTimes t = resolvePointTimes("time", sweep(1.0, last), last, PointTimeConfig());
  expectSweepOffsets(t, kStamp - last);
}

TEST(PointTimes, OusterNanosecondsFromTheStamp) {
  std::vector<double> raw = sweep(1e-9, kStamp);
  for (double& v : raw) v = std::round(v);  // uint32
  const PointTimes t = resolvePointTimes("t", raw, kStamp, PointTimeConfig());
  expectSweepOffsets(t);
  EXPECT_EQ(t.unit, "ns");
}

TEST(PointTimes, MillisecondsAndMicrosecondsAreTold) {
  EXPECT_EQ(resolvePointTimes("time", sweep(1e-3, kStamp), kStamp, PointTimeConfig()).unit, "ms");
  EXPECT_EQ(resolvePointTimes("t", sweep(1e-6, kStamp), kStamp, PointTimeConfig()).unit, "us");
}

TEST(PointTimes, HesaiAbsoluteFloatSeconds) {
  const PointTimes t = resolvePointTimes("timestamp", sweep(1.0, 0.0), kStamp, PointTimeConfig());
  expectSweepOffsets(t);
  EXPECT_TRUE(t.absolute);
  EXPECT_EQ(t.unit, "s");
}

TEST(PointTimes, RobosenseAbsoluteStampedAtTheLastPoint) {
  const double last = kStamp + 0.1 * (kPoints - 1) / kPoints;
  const PointTimes t = resolvePointTimes("timestamp", sweep(1.0, 0.0), last, PointTimeConfig());
  expectSweepOffsets(t, kStamp - last);
  EXPECT_TRUE(t.absolute);
}

TEST(PointTimes, LivoxOffsetTimeNanoseconds) {
  const PointTimes t =
      resolvePointTimes("offset_time", sweep(1e-9, kStamp), kStamp, PointTimeConfig());
  expectSweepOffsets(t);
  EXPECT_EQ(t.unit, "ns");
}

TEST(PointTimes, ConfiguredOriginAtTheLastPoint) {
  // Times count from the first point but the header stamp marks the last one.
  PointTimeConfig config;
  config.time_origin = "last_point";
  const double last = kStamp + 0.1 * (kPoints - 1) / kPoints;
  const PointTimes t = resolvePointTimes("time", sweep(1.0, kStamp), last, config);
  expectSweepOffsets(t, kStamp - last);
}

TEST(PointTimes, ConfiguredUnitIsUsed) {
  PointTimeConfig config;
  config.time_unit = "ms";
  const PointTimes t = resolvePointTimes("t", sweep(1e-3, kStamp), kStamp, config);
  expectSweepOffsets(t);
}

TEST(PointTimes, BadFieldsAreRejectedWithAReason) {
  const PointTimeConfig config;
  std::vector<double> constant(kPoints, 0.0);
  EXPECT_EQ(resolvePointTimes("time", constant, kStamp, config).reason, "constant");
  std::vector<double> nan = sweep(1.0, kStamp);
  nan[10] = std::numeric_limits<double>::quiet_NaN();
  const PointTimes bad = resolvePointTimes("time", nan, kStamp, config);
  EXPECT_FALSE(bad.ok);
  EXPECT_EQ(bad.reason, "non_finite");
  EXPECT_NE(bad.message.find("'time'"), std::string::npos) << bad.message;
  std::vector<double> decreasing = sweep(1.0, kStamp);
  std::reverse(decreasing.begin(), decreasing.end());
  EXPECT_EQ(resolvePointTimes("time", decreasing, kStamp, config).reason, "decreasing");
  // 0..1e5 fits no unit as one 0.1 s sweep near zero or near the stamp.
  EXPECT_EQ(resolvePointTimes("t", sweep(1e-6, kStamp + 1000.0, kStamp), kStamp, config).reason,
            "unit");
  EXPECT_EQ(resolvePointTimes("time", {}, kStamp, config).reason, "empty");
  // Absolute times a minute away from the stamp.
  EXPECT_FALSE(resolvePointTimes("timestamp", sweep(1.0, 0.0, kStamp - 60), kStamp, config).ok);
}

TEST(PointTimes, ConfigRejectsUnknownSpellings) {
  PointTimeConfig config;
  config.time_unit = "sec";
  EXPECT_THROW(config.validate(), std::runtime_error);
  config = PointTimeConfig();
  config.time_origin = "start";
  EXPECT_THROW(config.validate(), std::runtime_error);
}

TEST(Deskew, MovesEachPointToTheStampPose) {
  // A sensor turning at 90 deg/s and driving at 1.5 m/s sees a fixed point; each measurement,
  // moved by the motion up to its time, lands back on the point.
  BodyVelocity v;
  v.linear = Eigen::Vector3d(1.5, 0.0, 0.0);
  v.angular = Eigen::Vector3d(0.0, 0.0, M_PI / 2);
  const Eigen::Vector3d world_point(5.0, 2.0, 1.0);
  PointCloud scan;
  std::vector<float> offsets;
  for (int i = 0; i <= 100; ++i) {
    const double t = 0.001 * i;
    const Eigen::Vector3d seen = motionOver(v, t).inverse() * world_point;
    pcl::PointXYZI p;
    p.getVector3fMap() = seen.cast<float>();
    scan.push_back(p);
    offsets.push_back(static_cast<float>(t));
  }
  const double spread_before = (scan.points.back().getVector3fMap().cast<double>() -
                                scan.points.front().getVector3fMap().cast<double>())
                                   .norm();
  EXPECT_GT(spread_before, 0.5);  // the distortion is real
  const PointCloud out = deskew(scan, offsets, v);
  for (const auto& p : out.points) {
    EXPECT_LT((p.getVector3fMap().cast<double>() - world_point).norm(), 0.005);
  }
}

TEST(Deskew, ConstantVelocityFollowsTheArcOfATurnBothWaysInTime) {
  // A robot on a circle of radius 1 m at 1.5 m/s (86 deg/s): the velocity read off one 0.1 s
  // step gives every pose of the arc, before the stamp too (a sweep stamped at its last point).
  const double radius = 1.0, speed = 1.5;
  const auto onArc = [&](double t) {
    const double yaw = speed * t / radius;
    Pose3 T = Pose3::Identity();
    T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).matrix();
    T.translation() = Eigen::Vector3d(radius * std::sin(yaw), radius * (1.0 - std::cos(yaw)), 0.0);
    return T;
  };
  const BodyVelocity v = velocityOf(onArc(0.1), 0.1);
  EXPECT_NEAR(v.linear.x(), speed, 1e-9);  // the tangent, not the chord
  EXPECT_NEAR(v.linear.y(), 0.0, 1e-9);
  for (double t = -0.1; t <= 0.1001; t += 0.025) {
    const Pose3 expected = onArc(t), got = motionOver(v, t);
    EXPECT_LT((got.translation() - expected.translation()).norm(), 1e-9) << "t " << t;
    EXPECT_LT((got.linear() - expected.linear()).norm(), 1e-9) << "t " << t;
  }
}

TEST(Deskew, MismatchedOffsetsLeaveTheScanAsIs) {
  PointCloud scan;
  scan.push_back(pcl::PointXYZI());
  BodyVelocity v;
  v.linear = Eigen::Vector3d(1.0, 0.0, 0.0);
  EXPECT_EQ(deskew(scan, {}, v).size(), 1u);
  EXPECT_EQ(deskew(scan, {}, v).points[0].x, 0.0f);
}

TEST(Deskew, CarriedCovariancesTurnWithTheirPoints) {
  // A wall's plane measured 40 ms after the reference: deskewed first with no motion, then with a
  // 90 deg/s turn, its covariance turns by the turn's 3.6 deg, as if it had been estimated anew.
  const Eigen::Vector3d normal(1.0, 0.0, 0.0);
  const Eigen::Matrix3d plane = Eigen::Matrix3d::Identity() - 0.999 * normal * normal.transpose();
  BodyVelocity turn;
  turn.angular.z() = 0.5 * M_PI;
  turn.linear.x() = 1.5;
  const std::vector<float> times = {0.04f, -0.04f};
  const auto carried = redeskewCovariances({plane, plane}, times, BodyVelocity(), turn);
  ASSERT_EQ(carried.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    const Eigen::Matrix3d R = motionOver(turn, times[i]).linear();
    const Eigen::Vector3d turned = R * normal;
    EXPECT_NEAR((carried[i] * turned).norm(), 0.001, 1e-3);  // thin along the turned normal
    EXPECT_LT((carried[i] - R * plane * R.transpose()).norm(), 1e-6);
  }
  EXPECT_GT(std::abs(carried[0](0, 1)), 0.05);  // the normal did turn: 3.6 deg about z
  // Times of another length leave them as they were.
  EXPECT_EQ(redeskewCovariances({plane}, times, BodyVelocity(), turn)[0], plane);
}

}  // namespace
}  // namespace tacs
