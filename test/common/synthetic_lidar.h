// Analytic ray casting of a scene of axis-aligned boxes by a spinning LiDAR, with per-point
// ground truth: a point is ground when it hits the top face of a box marked walkable (floors,
// step treads). Used by the traversability tests and benchmark.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "tacs_graphs/common/types.h"

namespace tacs::test {

struct SceneBox {
  Eigen::Vector3d min, max;
  bool walkable = false;  // its top face is floor
};

struct Scene {
  std::vector<SceneBox> boxes;
  void add(double x0, double y0, double z0, double x1, double y1, double z1, bool walkable) {
    boxes.push_back({{x0, y0, z0}, {x1, y1, z1}, walkable});
  }
  /// A floor slab whose top is at height z.
  void floor(double x0, double y0, double x1, double y1, double z) {
    add(x0, y0, z - 0.1, x1, y1, z, true);
  }
};

struct LidarModel {
  int rings = 16;
  int columns = 1800;
  double vfov_min_deg = -15.0, vfov_max_deg = 15.0;
  double max_range = 100.0;
  static LidarModel vlp16() { return {16, 1800, -15.0, 15.0, 100.0}; }
  static LidarModel os0_128() { return {128, 1024, -45.0, 45.0, 50.0}; }
};

struct SyntheticScan {
  PointCloud cloud;                // in the base frame; intensity = index of the point
  std::vector<uint8_t> is_ground;  // ground truth per point
};

/// First hit of the ray o + t d (t > 0) with the box, and whether it enters through the top face.
inline bool intersectBox(const SceneBox& b, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                         double* t_hit, bool* top) {
  double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
  int axis = -1;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-12) {
      if (o[a] < b.min[a] || o[a] > b.max[a]) return false;
      continue;
    }
    double ta = (b.min[a] - o[a]) / d[a], tb = (b.max[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    if (ta > t0) {
      t0 = ta;
      axis = a;
    }
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  if (axis < 0) return false;  // the origin is inside the box
  *t_hit = t0;
  *top = axis == 2 && d.z() < 0;
  return true;
}

/// Casts one scan of `lidar` mounted at T_world_sensor; points are returned in the base frame
/// given by T_world_base, with Gaussian range noise.
inline SyntheticScan castScan(const Scene& scene, const LidarModel& lidar,
                              const Pose3& T_world_sensor, const Pose3& T_world_base,
                              double range_noise = 0.01, uint32_t seed = 1) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, range_noise);
  SyntheticScan out;
  const Pose3 T_base_sensor = T_world_base.inverse() * T_world_sensor;
  const Eigen::Vector3d o = T_world_sensor.translation();
  for (int r = 0; r < lidar.rings; ++r) {
    const double elev = (lidar.vfov_min_deg + (lidar.vfov_max_deg - lidar.vfov_min_deg) * r /
                                                  std::max(1, lidar.rings - 1)) *
                        M_PI / 180.0;
    for (int c = 0; c < lidar.columns; ++c) {
      const double az = 2.0 * M_PI * c / lidar.columns;
      const Eigen::Vector3d d_s(std::cos(elev) * std::cos(az), std::cos(elev) * std::sin(az),
                                std::sin(elev));
      const Eigen::Vector3d d = T_world_sensor.linear() * d_s;
      double best = lidar.max_range;
      bool ground = false, hit = false;
      for (const SceneBox& b : scene.boxes) {
        double t;
        bool top;
        if (intersectBox(b, o, d, &t, &top) && t < best) {
          best = t;
          ground = top && b.walkable;
          hit = true;
        }
      }
      if (!hit) continue;
      const Eigen::Vector3d p = T_base_sensor * ((best + noise(rng)) * d_s);
      pcl::PointXYZI q;
      q.x = static_cast<float>(p.x());
      q.y = static_cast<float>(p.y());
      q.z = static_cast<float>(p.z());
      q.intensity = static_cast<float>(out.cloud.size());
      out.cloud.push_back(q);
      out.is_ground.push_back(ground ? 1 : 0);
    }
  }
  return out;
}

/// An office-like room (8 x 6 m, 2.7 m high) with a desk, a cabinet and a doorway, for timing.
inline Scene roomScene() {
  Scene s;
  s.floor(-4, -3, 12, 3, 0.0);
  s.add(-4, -3, 2.7, 12, 3, 2.8, false);    // ceiling
  s.add(-4.15, -3, 0, -4, 3, 2.7, false);   // walls
  s.add(4, -3, 0, 4.15, -0.5, 2.7, false);  // wall with a 1 m doorway
  s.add(4, 0.5, 0, 4.15, 3, 2.7, false);
  s.add(-4, -3.15, 0, 12, -3, 2.7, false);
  s.add(-4, 3, 0, 12, 3.15, 2.7, false);
  s.add(12, -3, 0, 12.15, 3, 2.7, false);
  s.add(1.0, 1.8, 0.72, 2.6, 2.6, 0.75, false);  // desk top and legs
  s.add(1.0, 1.8, 0, 1.05, 1.85, 0.72, false);
  s.add(2.55, 1.8, 0, 2.6, 1.85, 0.72, false);
  s.add(-3.5, -2.5, 0, -2.9, -1.3, 1.9, false);  // cabinet
  return s;
}

}  // namespace tacs::test
