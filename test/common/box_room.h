// A synthetic indoor scene for odometry tests: a rectangular room with a few boxes, rendered by
// an analytic multi-ring LiDAR (VLP-16 layout by default) with Gaussian range noise.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "tacs_graphs/common/types.h"

namespace tacs::test {

struct Box {
  Eigen::Vector3d lo, hi;
};

struct BoxRoom {
  Box room{{0.0, 0.0, 0.0}, {10.0, 7.0, 2.8}};  // the walls, floor and ceiling (seen from inside)
  std::vector<Box> obstacles = {{{2.0, 1.0, 0.0}, {3.0, 1.6, 0.9}},
                                {{6.5, 4.5, 0.0}, {7.3, 6.9, 1.8}},
                                {{4.0, 5.5, 0.0}, {4.4, 5.9, 2.8}},  // a pillar
                                {{8.2, 0.8, 0.0}, {9.0, 1.5, 0.6}}};
};

// Distance along the unit ray (o, d) to the first surface, or +inf.
inline double castRay(const BoxRoom& scene, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  double best = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {  // exit through the room's walls
    if (d[a] > 1e-12) best = std::min(best, (scene.room.hi[a] - o[a]) / d[a]);
    if (d[a] < -1e-12) best = std::min(best, (scene.room.lo[a] - o[a]) / d[a]);
  }
  for (const Box& b : scene.obstacles) {  // slab test: entry distance of each box
    double t0 = 0.0, t1 = best;
    for (int a = 0; a < 3 && t0 <= t1; ++a) {
      if (std::abs(d[a]) < 1e-12) {
        if (o[a] < b.lo[a] || o[a] > b.hi[a]) t0 = t1 + 1.0;
        continue;
      }
      double ta = (b.lo[a] - o[a]) / d[a], tb = (b.hi[a] - o[a]) / d[a];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    if (t0 <= t1 && t0 > 0.0) best = std::min(best, t0);
  }
  return best;
}

// One scan in the sensor frame from sensor pose T_world_sensor: `rings` beams over +-15 deg,
// `columns` azimuth steps, range noise std `noise_m`.
inline PointCloud renderScan(const BoxRoom& scene, const Pose3& T_world_sensor, unsigned seed,
                             int rings = 16, int columns = 900, double noise_m = 0.01) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_m);
  PointCloud cloud;
  const Eigen::Vector3d o = T_world_sensor.translation();
  for (int r = 0; r < rings; ++r) {
    const double elev = (-15.0 + 30.0 * r / (rings - 1)) * M_PI / 180.0;
    for (int c = 0; c < columns; ++c) {
      const double az = 2.0 * M_PI * c / columns;
      const Eigen::Vector3d d_s(std::cos(elev) * std::cos(az), std::cos(elev) * std::sin(az),
                                std::sin(elev));
      const double range = castRay(scene, o, T_world_sensor.linear() * d_s);
      if (!std::isfinite(range) || range > 100.0) continue;
      const Eigen::Vector3d p = d_s * (range + noise(rng));
      pcl::PointXYZI q;
      q.x = static_cast<float>(p.x());
      q.y = static_cast<float>(p.y());
      q.z = static_cast<float>(p.z());
      q.intensity = static_cast<float>(r);
      cloud.points.push_back(q);
    }
  }
  cloud.width = static_cast<uint32_t>(cloud.points.size());
  cloud.height = 1;
  return cloud;
}

// Translation error [m] and rotation error [deg] between two poses.
inline double translationError(const Pose3& a, const Pose3& b) {
  return (a.translation() - b.translation()).norm();
}
inline double rotationErrorDeg(const Pose3& a, const Pose3& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180.0 / M_PI;
}

}  // namespace tacs::test
