#include "tacs_graphs/odometry/deskew.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace tacs {

namespace {
constexpr double kGridStepS = 5e-4;  // [s] time resolution of the per-point transforms
}

Pose3 motionOver(const BodyVelocity& velocity, double t) {
  Pose3 T = Pose3::Identity();
  T.translation() = velocity.linear * t;
  const Eigen::Vector3d w = velocity.angular * t;
  if (w.norm() > 0.0) T.linear() = Eigen::AngleAxisd(w.norm(), w.normalized()).matrix();
  return T;
}

PointCloud deskew(const PointCloud& scan, const std::vector<float>& offset_s,
                  const BodyVelocity& velocity) {
  PointCloud out = scan;
  if (offset_s.size() != scan.size() || scan.empty()) return out;
  const auto [lo, hi] = std::minmax_element(offset_s.begin(), offset_s.end());
  const double t0 = *lo;
  const size_t cells = static_cast<size_t>(std::ceil((*hi - t0) / kGridStepS)) + 1;
  std::vector<Eigen::Affine3f> grid(cells);
  for (size_t c = 0; c < cells; ++c) {
    grid[c] = motionOver(velocity, t0 + c * kGridStepS).cast<float>();
  }
  for (size_t i = 0; i < out.size(); ++i) {
    const size_t c =
        std::min(cells - 1, static_cast<size_t>(std::lround((offset_s[i] - t0) / kGridStepS)));
    auto& p = out.points[i];
    p.getVector3fMap() = grid[c] * p.getVector3fMap();
  }
  return out;
}

}  // namespace tacs
