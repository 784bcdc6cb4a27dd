#include "tacs_graphs/odometry/deskew.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace tacs {

namespace {
constexpr double kGridStepS = 5e-4;  // [s] time resolution of the per-point transforms

// V(w) of the SE(3) exponential: translation = V(w) * v for the twist (v, w) over unit time.
Eigen::Matrix3d leftJacobian(const Eigen::Vector3d& w) {
  const double theta = w.norm();
  const Eigen::Matrix3d k = skew(w);
  if (theta < 1e-6) return Eigen::Matrix3d::Identity() + 0.5 * k;
  const double t2 = theta * theta;
  return Eigen::Matrix3d::Identity() + (1.0 - std::cos(theta)) / t2 * k +
         (theta - std::sin(theta)) / (t2 * theta) * k * k;
}
}  // namespace

Pose3 motionOver(const BodyVelocity& velocity, double t) {
  Pose3 T = Pose3::Identity();
  const Eigen::Vector3d w = velocity.angular * t;
  if (w.norm() > 0.0) T.linear() = Eigen::AngleAxisd(w.norm(), w.normalized()).matrix();
  T.translation() = leftJacobian(w) * (velocity.linear * t);
  return T;
}

BodyVelocity velocityOf(const Pose3& step, double dt) {
  BodyVelocity v;
  if (!(dt > 0.0)) return v;
  const Eigen::AngleAxisd aa(step.linear());
  const Eigen::Vector3d w = aa.angle() * aa.axis();
  v.angular = w / dt;
  v.linear = leftJacobian(w).inverse() * step.translation() / dt;
  return v;
}

MotionGrid::MotionGrid(const BodyVelocity& velocity, double t_lo, double t_hi) : t_lo_(t_lo) {
  const size_t cells = static_cast<size_t>(std::ceil((t_hi - t_lo) / kGridStepS)) + 1;
  poses_.resize(cells);
  for (size_t c = 0; c < cells; ++c) poses_[c] = motionOver(velocity, t_lo + c * kGridStepS);
}

size_t MotionGrid::cell(double t) const {
  return std::min(poses_.size() - 1,
                  static_cast<size_t>(std::max(0L, std::lround((t - t_lo_) / kGridStepS))));
}

PointCloud deskew(const PointCloud& scan, const std::vector<float>& offset_s,
                  const BodyVelocity& velocity) {
  PointCloud out = scan;
  if (offset_s.size() != scan.size() || scan.empty()) return out;
  const auto [lo, hi] = std::minmax_element(offset_s.begin(), offset_s.end());
  const MotionGrid motion(velocity, *lo, *hi);
  std::vector<Eigen::Affine3f> grid(motion.size());
  for (size_t c = 0; c < grid.size(); ++c) grid[c] = motion.pose(c).cast<float>();
  for (size_t i = 0; i < out.size(); ++i) {
    auto& p = out.points[i];
    p.getVector3fMap() = grid[motion.cell(offset_s[i])] * p.getVector3fMap();
  }
  return out;
}

std::vector<Eigen::Matrix3d> redeskewCovariances(const std::vector<Eigen::Matrix3d>& covariances,
                                                 const std::vector<float>& offset_s,
                                                 const BodyVelocity& from, const BodyVelocity& to) {
  if (offset_s.size() != covariances.size() || covariances.empty()) return covariances;
  const auto [lo, hi] = std::minmax_element(offset_s.begin(), offset_s.end());
  const MotionGrid before(from, *lo, *hi), after(to, *lo, *hi);
  std::vector<Eigen::Matrix3d> change(before.size());
  for (size_t c = 0; c < change.size(); ++c) {
    change[c] = after.pose(c).linear() * before.pose(c).linear().transpose();
  }
  std::vector<Eigen::Matrix3d> out(covariances.size());
  for (size_t i = 0; i < out.size(); ++i) {
    const Eigen::Matrix3d& R = change[before.cell(offset_s[i])];
    out[i] = R * covariances[i] * R.transpose();
  }
  return out;
}

}  // namespace tacs
