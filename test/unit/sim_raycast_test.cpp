#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "tacs_graphs/sim/ray_caster.h"
#include "tacs_graphs/sim/scan_stream.h"

namespace tacs::sim {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

/// A closed 10 x 6 m box room (walls 0.2 m thick centred on its outline), 3 m high.
World boxRoom(const std::string& model) {
  World w;
  const Eigen::Vector2d c[4] = {{0, 0}, {10, 0}, {10, 6}, {0, 6}};
  for (int i = 0; i < 4; ++i) {
    Wall wall;
    // Extend by half the thickness so the corners close.
    const Eigen::Vector2d d = (c[(i + 1) % 4] - c[i]).normalized();
    wall.from = c[i] - 0.1 * d, wall.to = c[(i + 1) % 4] + 0.1 * d;
    wall.z_max = 3.0, wall.thickness = 0.2;
    w.walls.push_back(wall);
  }
  const Polygon2 poly(c, c + 4);
  w.floors.push_back({poly, 0.0, 0.3});
  w.ceilings.push_back({poly, 3.0, 0.5});
  w.trajectory.waypoints = {{4, 3, NAN}, {6, 3, NAN}};
  w.trajectory.jitter_deg = 0.0, w.trajectory.jitter_z_m = 0.0;
  w.trajectory.speed_mps = 1.0;
  applySensorPreset(model, &w.sensor);
  w.sensor.range_noise_std_m = 0.01;
  w.sensor.dropout_prob = 0.0;
  w.sensor.mount_height_m = 1.0;
  return w;
}

TEST(SimRayCast, AnalyticRangesInABoxRoom) {
  const World w = boxRoom("vlp16");
  RayCaster caster(w, 0.7);
  RayHit hit;
  const Eigen::Vector3d o(4.0, 3.0, 1.0);
  // Inner faces at x = 0.1, 9.9, y = 0.1, 5.9; floor z = 0, ceiling 3.
  ASSERT_TRUE(caster.cast(o, Eigen::Vector3d::UnitX(), 100, &hit));
  EXPECT_NEAR(hit.range, 5.9, 1e-9);
  EXPECT_TRUE(hit.normal.isApprox(-Eigen::Vector3d::UnitX()));
  ASSERT_TRUE(caster.cast(o, -Eigen::Vector3d::UnitY(), 100, &hit));
  EXPECT_NEAR(hit.range, 2.9, 1e-9);
  ASSERT_TRUE(caster.cast(o, -Eigen::Vector3d::UnitZ(), 100, &hit));
  EXPECT_NEAR(hit.range, 1.0, 1e-9);
  EXPECT_TRUE(hit.normal.isApprox(Eigen::Vector3d::UnitZ()));
  const Eigen::Vector3d diag = Eigen::Vector3d(-1, 1, 0).normalized();
  ASSERT_TRUE(caster.cast(o, diag, 100, &hit));
  EXPECT_NEAR(hit.range, 2.9 * std::sqrt(2.0), 1e-9);                 // hits y = 5.9 at x = 1.1
  EXPECT_FALSE(caster.cast(o, Eigen::Vector3d::UnitX(), 5.0, &hit));  // beyond max range
  // A rotated box: a 1 m cube at (7, 3) turned 45 deg shows its corner at x = 7 - sqrt(0.5).
  World wb = w;
  wb.boxes.push_back({Eigen::Vector3d(7, 3, 1.0), Eigen::Vector3d::Ones(), 45.0, 0.7});
  RayCaster caster_b(wb, 1.0);
  ASSERT_TRUE(caster_b.cast(o, Eigen::Vector3d::UnitX(), 100, &hit));
  EXPECT_NEAR(hit.range, 3.0 - std::sqrt(0.5), 1e-9);
  EXPECT_EQ(caster_b.primitiveCount(), 7u);
}

TEST(SimRayCast, ScanRangesMatchGeometryWithinNoise) {
  const World w = boxRoom("vlp16");
  SimOptions opt;
  ScanStream stream(w, opt);
  SimScan scan;
  ASSERT_TRUE(stream.next(&scan));
  const Pose3 T = scan.T_world_base * stream.baseToSensor();
  EXPECT_NEAR(T.translation().z(), 1.0, 1e-9);
  int checked = 0;
  for (const auto& p : scan.points) {
    const Eigen::Vector3d q = T * Eigen::Vector3d(p.x, p.y, p.z);
    // Distance of the world point to the nearest surface of the room.
    const double d = std::min({std::abs(q.x() - 0.1), std::abs(q.x() - 9.9), std::abs(q.y() - 0.1),
                               std::abs(q.y() - 5.9), std::abs(q.z()), std::abs(q.z() - 3.0)});
    EXPECT_LT(d, 0.06);  // 6 sigma
    ++checked;
  }
  EXPECT_GT(checked, 16 * 1800 * 0.99);  // closed room: (almost) every ray returns
}

TEST(SimRayCast, RingElevationPatternOfEachModel) {
  const std::map<std::string, std::pair<int, double>> models = {
      {"vlp16", {16, 15.0}}, {"os1_64", {64, 22.5}}, {"os0_128", {128, 45.0}}};
  for (const auto& [model, spec] : models) {
    SCOPED_TRACE(model);
    World w = boxRoom(model);
    w.sensor.range_noise_std_m = 0.0;
    ScanStream stream(w, SimOptions{});
    SimScan scan;
    ASSERT_TRUE(stream.next(&scan));
    std::map<int, std::pair<double, double>> el;  // ring -> min, max elevation seen
    for (const auto& p : scan.points) {
      const double e = std::atan2(p.z, std::hypot(p.x, p.y)) / kDeg;
      auto it = el.emplace(p.ring, std::make_pair(e, e)).first;
      it->second.first = std::min(it->second.first, e);
      it->second.second = std::max(it->second.second, e);
    }
    ASSERT_EQ(static_cast<int>(el.size()), spec.first);
    for (const auto& [ring, range] : el) {
      const double expected = -spec.second + 2.0 * spec.second * ring / (spec.first - 1);
      EXPECT_NEAR(range.first, expected, 1e-3) << ring;
      EXPECT_NEAR(range.second, expected, 1e-3) << ring;
    }
  }
}

TEST(SimRayCast, CustomModelAndTimes) {
  World w = boxRoom("vlp16");
  w.sensor.model = "custom";
  w.sensor.rings = 4, w.sensor.vfov_deg = 20.0, w.sensor.hres_deg = 1.0;
  w.sensor.dropout_prob = 0.5;
  ScanStream stream(w, SimOptions{});
  SimScan scan;
  ASSERT_TRUE(stream.next(&scan));
  EXPECT_GT(scan.points.size(), 4 * 360 * 0.4);
  EXPECT_LT(scan.points.size(), 4 * 360 * 0.6);  // half dropped
  float last = -1.0f;
  for (const auto& p : scan.points) {
    EXPECT_LT(p.ring, 4);
    EXPECT_GE(p.time, last);  // firings in time order
    EXPECT_LT(p.time, 0.1f);
    EXPECT_GE(p.intensity, 0.0f);
    EXPECT_LE(p.intensity, 255.0f);
    last = p.time;
  }
  EXPECT_GT(last, 0.09f);
}

}  // namespace
}  // namespace tacs::sim
