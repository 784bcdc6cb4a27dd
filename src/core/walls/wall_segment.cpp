#include "tacs_graphs/walls/wall_segment.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tacs {

Eigen::Vector2d wallAxis(const Eigen::Vector3d& normal) {
  const Eigen::Vector2d axis(-normal.y(), normal.x());  // z x n
  const double norm = axis.norm();
  return norm > 1e-12 ? Eigen::Vector2d(axis / norm) : Eigen::Vector2d::UnitX();
}

double planeDistance(const Eigen::Vector3d& normal, double d, const Eigen::Vector2d& xy, double z) {
  return normal.x() * xy.x() + normal.y() * xy.y() + normal.z() * z + d;
}

Eigen::Vector2d projectOntoWallLine(const Eigen::Vector3d& normal, double d,
                                    const Eigen::Vector2d& xy, double z) {
  const Eigen::Vector2d h = normal.head<2>();
  const double h2 = h.squaredNorm();
  if (h2 < 1e-12) return xy;  // a horizontal plane has no wall line
  return xy - h * (planeDistance(normal, d, xy, z) / h2);
}

void transformPlane(const Pose3& T_a_b, const Eigen::Vector3d& normal_b, double d_b,
                    Eigen::Vector3d* normal_a, double* d_a) {
  *normal_a = T_a_b.linear() * normal_b;
  *d_a = d_b - normal_a->dot(T_a_b.translation());
}

WallSegment transformWall(const WallSegment& wall_b, const Pose3& T_a_b) {
  WallSegment wall_a = wall_b;
  transformPlane(T_a_b, wall_b.normal, wall_b.d, &wall_a.normal, &wall_a.d);
  const double z_mid = 0.5 * (wall_b.z_min + wall_b.z_max);
  wall_a.z_min = std::numeric_limits<double>::infinity();
  wall_a.z_max = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < 2; ++i) {
    const Eigen::Vector2d& e = wall_b.endpoints[i];
    wall_a.endpoints[i] = (T_a_b * Eigen::Vector3d(e.x(), e.y(), z_mid)).head<2>();
    for (double z : {wall_b.z_min, wall_b.z_max}) {
      const double za = (T_a_b * Eigen::Vector3d(e.x(), e.y(), z)).z();
      wall_a.z_min = std::min(wall_a.z_min, za);
      wall_a.z_max = std::max(wall_a.z_max, za);
    }
  }
  // Keep the endpoints ordered along the (rotated) wall axis.
  const Eigen::Vector2d axis = wallAxis(wall_a.normal);
  if (axis.dot(wall_a.endpoints[1] - wall_a.endpoints[0]) < 0.0) {
    std::swap(wall_a.endpoints[0], wall_a.endpoints[1]);
  }
  return wall_a;
}

}  // namespace tacs
