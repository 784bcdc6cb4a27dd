// Cost functors of the hierarchical factor graph (Ceres, automatic differentiation).
//
// Parameter blocks:
//   keyframe: t[3] (map frame, metres) and q[4] (Eigen order x y z w, on EigenQuaternionManifold);
//   wall:     w[2] = (theta, d): the vertical plane n . p + d = 0 with n = (cos theta, sin theta,
//   0)
//             in the map frame. Walls are vertical in the gravity-aligned map, so two parameters
//             describe them without gauge freedom;
//   room:     c[2], the room centre in the map xy plane.
// Residuals are whitened: each functor carries its square-root information.
#pragma once

#include <ceres/rotation.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace tacs {

/// Odometry and loop-closure edge: the pose of keyframe b in the frame of keyframe a is measured
/// as T_ab. Residual (6): [translation error in frame a; 2 * vec(q_ab^-1 * q_a^-1 * q_b)].
struct RelativePoseFactor {
  RelativePoseFactor(const Eigen::Isometry3d& T_ab, const Eigen::Matrix<double, 6, 6>& sqrt_info)
      : t_ab(T_ab.translation()), q_ab(T_ab.rotation()), sqrt_info(sqrt_info) {}

  template <typename T>
  bool operator()(const T* ta, const T* qa, const T* tb, const T* qb, T* residual) const {
    Eigen::Map<const Eigen::Matrix<T, 3, 1>> p_a(ta), p_b(tb);
    Eigen::Map<const Eigen::Quaternion<T>> q_a(qa), q_b(qb);
    const Eigen::Quaternion<T> q_a_inv = q_a.conjugate();
    const Eigen::Matrix<T, 3, 1> t_est = q_a_inv * (p_b - p_a);
    const Eigen::Quaternion<T> q_err = q_ab.cast<T>().conjugate() * (q_a_inv * q_b);
    Eigen::Map<Eigen::Matrix<T, 6, 1>> r(residual);
    r.template head<3>() = t_est - t_ab.cast<T>();
    r.template tail<3>() = T(2.0) * q_err.vec();
    r.applyOnTheLeft(sqrt_info.cast<T>());
    return true;
  }

  Eigen::Vector3d t_ab;
  Eigen::Quaterniond q_ab;
  Eigen::Matrix<double, 6, 6> sqrt_info;
};

/// Map-frame wall (theta, d) expressed in a keyframe's base frame: n_b = R^T n, d_b = d + n . t.
template <typename T>
void wallInBase(const T* t, const T* q, const T* wall, Eigen::Matrix<T, 3, 1>* n_b, T* d_b) {
  Eigen::Map<const Eigen::Matrix<T, 3, 1>> p(t);
  Eigen::Map<const Eigen::Quaternion<T>> rot(q);
  const Eigen::Matrix<T, 3, 1> n(cos(wall[0]), sin(wall[0]), T(0));
  *n_b = rot.conjugate() * n;
  *d_b = wall[1] + n.dot(p);
}

/// Keyframe-to-wall factor (paper Sec. III-B-1, S-Graphs' plane edge): a wall observed in the base
/// frame as (n_obs, d_obs). Residual (4): [(n_b - n_obs) / sigma_n; (d_b - d_obs) / sigma_d].
struct WallObservationFactor {
  WallObservationFactor(const Eigen::Vector3d& n_obs, double d_obs, double sigma_n, double sigma_d)
      : n_obs(n_obs), d_obs(d_obs), inv_sigma_n(1.0 / sigma_n), inv_sigma_d(1.0 / sigma_d) {}

  template <typename T>
  bool operator()(const T* t, const T* q, const T* wall, T* residual) const {
    Eigen::Matrix<T, 3, 1> n_b;
    T d_b;
    wallInBase(t, q, wall, &n_b, &d_b);
    for (int i = 0; i < 3; ++i) residual[i] = (n_b[i] - T(n_obs[i])) * T(inv_sigma_n);
    residual[3] = (d_b - T(d_obs)) * T(inv_sigma_d);
    return true;
  }

  Eigen::Vector3d n_obs;
  double d_obs;
  double inv_sigma_n, inv_sigma_d;
};

/// Room factor for one pair of facing walls (paper Sec. III-B-3): the room centre lies midway
/// between them, i.e. its signed distances to both walls (normals face into the room) are equal.
/// A four-wall room has two of these, a corridor one. Residual (1), metres / sigma.
struct RoomPairFactor {
  explicit RoomPairFactor(double sigma) : inv_sigma(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* c, const T* wall_a, const T* wall_b, T* residual) const {
    const T dist_a = cos(wall_a[0]) * c[0] + sin(wall_a[0]) * c[1] + wall_a[1];
    const T dist_b = cos(wall_b[0]) * c[0] + sin(wall_b[0]) * c[1] + wall_b[1];
    residual[0] = (dist_a - dist_b) * T(inv_sigma);
    return true;
  }

  double inv_sigma;
};

/// A corridor's centre is only defined across the corridor; along it, it is anchored to the centre
/// of its free space (measured, fixed). Residual (1): the along-wall offset / sigma.
struct CorridorAnchorFactor {
  CorridorAnchorFactor(const Eigen::Vector2d& anchor, double sigma)
      : anchor(anchor), inv_sigma(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* c, const T* wall, T* residual) const {
    const T along = -sin(wall[0]) * (c[0] - T(anchor.x())) + cos(wall[0]) * (c[1] - T(anchor.y()));
    residual[0] = along * T(inv_sigma);
    return true;
  }

  Eigen::Vector2d anchor;
  double inv_sigma;
};

/// Prior on the anchor keyframe's orientation: yaw is the map's gauge and held (sigma_yaw tiny),
/// roll and pitch only softly, so the vertical walls (Sec. III-B-1) level the map when the first
/// scan was taken on a tilt. Residual (3): 2 * vec(q0^-1 * q) / [sigma_tilt, sigma_tilt,
/// sigma_yaw], the rotation error in the anchor's frame.
struct AnchorOrientationFactor {
  AnchorOrientationFactor(const Eigen::Quaterniond& q0, double sigma_tilt, double sigma_yaw)
      : q0(q0), inv_sigma(1.0 / sigma_tilt, 1.0 / sigma_tilt, 1.0 / sigma_yaw) {}

  template <typename T>
  bool operator()(const T* q, T* residual) const {
    Eigen::Map<const Eigen::Quaternion<T>> rot(q);
    const Eigen::Quaternion<T> err = q0.cast<T>().conjugate() * rot;
    for (int i = 0; i < 3; ++i) residual[i] = T(2.0) * err.vec()[i] * T(inv_sigma[i]);
    return true;
  }

  Eigen::Quaterniond q0;
  Eigen::Vector3d inv_sigma;
};

/// Wall-to-wall edge of room merging (paper eq. 4): a wall of a newly detected room that the merged
/// room already holds must coincide with it. Residual (2): [wrapped angle difference / sigma_theta;
/// d difference / sigma_d].
struct WallToWallFactor {
  WallToWallFactor(double sigma_theta, double sigma_d)
      : inv_sigma_theta(1.0 / sigma_theta), inv_sigma_d(1.0 / sigma_d) {}

  template <typename T>
  bool operator()(const T* wall_a, const T* wall_b, T* residual) const {
    // sin/cos keep the angle difference continuous across +-pi.
    const T dtheta = atan2(sin(wall_b[0] - wall_a[0]), cos(wall_b[0] - wall_a[0]));
    residual[0] = dtheta * T(inv_sigma_theta);
    residual[1] = (wall_b[1] - wall_a[1]) * T(inv_sigma_d);
    return true;
  }

  double inv_sigma_theta, inv_sigma_d;
};

}  // namespace tacs
