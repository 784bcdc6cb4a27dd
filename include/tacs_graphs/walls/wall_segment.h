// A wall observation (a bounded vertical plane) and the plane geometry shared by the wall module.
//
// Plane convention (paper Sec. III-B-1): n.p + d = 0 with |n| = 1. In the frame the plane was
// observed in (the gravity-aligned base frame), the normal faces the sensor at the origin, so
// d >= 0. Transformed into the map frame the normal keeps that facing direction: it points into
// the room the wall was seen from.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "tacs_graphs/common/types.h"

namespace tacs {

struct WallSegment {
  /// Unit normal, facing the sensor in the observation frame.
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  /// Plane offset (m): n.p + d = 0; >= 0 in the observation frame.
  double d = 0.0;
  /// Number of points (after voxel downsampling) supporting the segment.
  uint32_t inliers = 0;
  /// Vertical walls: the segment's extent, two points on the plane's line in the xy plane (m),
  /// ordered along wallAxis(normal). Horizontal planes: the xy bounding box [min, max] of inliers.
  Eigen::Vector2d endpoints[2] = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  /// Height range of the inliers (m).
  double z_min = 0.0;
  double z_max = 0.0;

  /// Distance between the endpoints (m).
  double length() const { return (endpoints[1] - endpoints[0]).norm(); }
  /// Middle of the segment in xy (m).
  Eigen::Vector2d midpoint() const { return 0.5 * (endpoints[0] + endpoints[1]); }
};

/// Horizontal unit direction along a vertical wall with this normal: z x n, normalised. Endpoints
/// are ordered so that endpoints[1] lies further along this axis than endpoints[0].
Eigen::Vector2d wallAxis(const Eigen::Vector3d& normal);

/// Signed distance of the point (xy, z) from the plane (n, d) (m).
double planeDistance(const Eigen::Vector3d& normal, double d, const Eigen::Vector2d& xy, double z);

/// Orthogonal projection of an xy point onto the plane's line at height z (for vertical planes).
Eigen::Vector2d projectOntoWallLine(const Eigen::Vector3d& normal, double d,
                                    const Eigen::Vector2d& xy, double z);

/// Transforms a plane (n, d) given in frame b into frame a: n_a = R n_b, d_a = d_b - n_a.t.
void transformPlane(const Pose3& T_a_b, const Eigen::Vector3d& normal_b, double d_b,
                    Eigen::Vector3d* normal_a, double* d_a);

/// The segment expressed in frame a: plane, endpoints (taken at mid height) and z range (the
/// same span about the moved middle; exact for a level transform). The normal keeps its facing direction, so d may become negative.
WallSegment transformWall(const WallSegment& wall_b, const Pose3& T_a_b);

}  // namespace tacs
