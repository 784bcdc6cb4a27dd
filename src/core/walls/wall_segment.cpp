#include "tacs_graphs/walls/wall_segment.h"

#include <algorithm>
#include <cmath>

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
  // The height range moves with the segment's middle and keeps its span: a wall's height is its
  // own, and a wall taken into a tilted frame and back (Pipeline: the levelled floor frame, the
  // base, the map) keeps it instead of growing by the tilt twice.
  const double z_mid = 0.5 * (wall_b.z_min + wall_b.z_max);
  const double half_span = 0.5 * (wall_b.z_max - wall_b.z_min);
  for (int i = 0; i < 2; ++i) {
    const Eigen::Vector2d& e = wall_b.endpoints[i];
    wall_a.endpoints[i] = (T_a_b * Eigen::Vector3d(e.x(), e.y(), z_mid)).head<2>();
  }
  const Eigen::Vector2d mid_b = 0.5 * (wall_b.endpoints[0] + wall_b.endpoints[1]);
  const double z_mid_a = (T_a_b * Eigen::Vector3d(mid_b.x(), mid_b.y(), z_mid)).z();
  wall_a.z_min = z_mid_a - half_span;
  wall_a.z_max = z_mid_a + half_span;
  // Keep the endpoints ordered along the (rotated) wall axis.
  const Eigen::Vector2d axis = wallAxis(wall_a.normal);
  if (axis.dot(wall_a.endpoints[1] - wall_a.endpoints[0]) < 0.0) {
    std::swap(wall_a.endpoints[0], wall_a.endpoints[1]);
  }
  return wall_a;
}

}  // namespace tacs
