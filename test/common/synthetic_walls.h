// Synthetic point clouds of rooms for the wall tests: planar patches sampled on a grid with
// Gaussian noise (area sampling, not a LiDAR model), in a frame with z up.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <random>
#include <vector>

#include "tacs_graphs/common/types.h"

namespace tacs::test {

struct SyntheticScene {
  double spacing = 0.05;    // grid step on every patch (m)
  double noise_std = 0.01;  // Gaussian noise per axis (m)
  std::mt19937 rng{7};
  PointCloud cloud;

  void add(const Eigen::Vector3d& p) {
    std::normal_distribution<double> n(0.0, noise_std);
    pcl::PointXYZI q;
    q.x = static_cast<float>(p.x() + n(rng));
    q.y = static_cast<float>(p.y() + n(rng));
    q.z = static_cast<float>(p.z() + n(rng));
    q.intensity = 0.f;
    cloud.push_back(q);
  }

  /// Vertical wall from a to b (xy), between heights z0 and z1.
  void wall(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double z0, double z1) {
    const double len = (b - a).norm();
    for (double s = 0.0; s <= len; s += spacing) {
      const Eigen::Vector2d xy = a + (b - a) * (s / len);
      for (double z = z0; z <= z1; z += spacing) add({xy.x(), xy.y(), z});
    }
  }

  /// Horizontal rectangle [x0, x1] x [y0, y1] at height z.
  void slab(double x0, double x1, double y0, double y1, double z) {
    for (double x = x0; x <= x1; x += spacing) {
      for (double y = y0; y <= y1; y += spacing) add({x, y, z});
    }
  }

  /// Closed rectangular room [x0, x1] x [y0, y1] with floor and ceiling.
  void boxRoom(double x0, double x1, double y0, double y1, double z_floor, double z_ceiling) {
    wall({x0, y0}, {x1, y0}, z_floor, z_ceiling);
    wall({x1, y0}, {x1, y1}, z_floor, z_ceiling);
    wall({x1, y1}, {x0, y1}, z_floor, z_ceiling);
    wall({x0, y1}, {x0, y0}, z_floor, z_ceiling);
    slab(x0, x1, y0, y1, z_floor);
    slab(x0, x1, y0, y1, z_ceiling);
  }

  /// Rooms [0, 5] x [0, 4] and [5, 10] x [0, 4], walls 0..2.5 m high, with a floor; the
  /// partition x = 5 has a door at y 1..2.
  void twoRoomsWithDoor() {
    wall({0, 0}, {10, 0}, 0.0, 2.5);
    wall({10, 0}, {10, 4}, 0.0, 2.5);
    wall({10, 4}, {0, 4}, 0.0, 2.5);
    wall({0, 4}, {0, 0}, 0.0, 2.5);
    wall({5, 0}, {5, 1}, 0.0, 2.5);
    wall({5, 2}, {5, 4}, 0.0, 2.5);
    slab(0, 10, 0, 4, 0.0);
  }

  /// Applies T to every point.
  void transform(const Pose3& T) {
    for (auto& q : cloud.points) {
      const Eigen::Vector3d p = T * Eigen::Vector3d(q.x, q.y, q.z);
      q.x = static_cast<float>(p.x());
      q.y = static_cast<float>(p.y());
      q.z = static_cast<float>(p.z());
    }
  }
};

}  // namespace tacs::test
