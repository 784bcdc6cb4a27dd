#include "tacs_graphs/walls/dominant_axes.h"

#include <cmath>

#include "tacs_graphs/common/config.h"
#include "tacs_graphs/walls/wall_map.h"

namespace tacs {

namespace {
constexpr double kQuarter = M_PI / 2.0;  // the axes repeat every 90 deg
constexpr double kDeg = M_PI / 180.0;

// Angle folded into [0, 90 deg).
double foldQuarter(double a) {
  a = std::fmod(a, kQuarter);
  return a < 0.0 ? a + kQuarter : a;
}

// Smallest difference of two angles modulo 90 deg, in [0, 45 deg].
double quarterDistance(double a, double b) {
  const double diff = foldQuarter(a - b);
  return std::min(diff, kQuarter - diff);
}
}  // namespace

void DominantAxesConfig::validate() const {
  const std::string p = "walls.axes.";
  requireConfig(bin_deg > 0.0 && bin_deg <= 10.0, p + "bin_deg", "must be in (0, 10]");
  requireConfig(smoothing_deg >= 0.0, p + "smoothing_deg", "must be >= 0");
  requireConfig(window_deg > 0.0 && window_deg <= 45.0, p + "window_deg", "must be in (0, 45]");
  requireConfig(min_support >= 0.0, p + "min_support_m", "must be >= 0");
}

Eigen::Vector2d DominantAxes::xAxis() const { return {std::cos(yaw), std::sin(yaw)}; }
Eigen::Vector2d DominantAxes::yAxis() const { return {-std::sin(yaw), std::cos(yaw)}; }

DominantAxes estimateDominantAxes(const std::vector<Eigen::Vector3d>& normals,
                                  const std::vector<double>& weights,
                                  const DominantAxesConfig& config) {
  DominantAxes axes;
  const int bins = std::max(1, static_cast<int>(std::lround(90.0 / config.bin_deg)));
  const double bin = kQuarter / bins;
  std::vector<double> angles, w;
  std::vector<double> hist(bins, 0.0);
  double total = 0.0;
  for (size_t i = 0; i < normals.size() && i < weights.size(); ++i) {
    if (normals[i].head<2>().norm() < 0.5 || weights[i] <= 0.0) continue;  // not a wall
    angles.push_back(foldQuarter(std::atan2(normals[i].y(), normals[i].x())));
    w.push_back(weights[i]);
    hist[std::min(bins - 1, static_cast<int>(angles.back() / bin))] += weights[i];
    total += weights[i];
  }
  if (angles.empty()) return axes;

  // Circular Gaussian smoothing of the histogram, then its peak.
  const double sigma_bins = config.smoothing_deg * kDeg / bin;
  const int radius = static_cast<int>(std::ceil(3.0 * sigma_bins));
  int peak = 0;
  double peak_value = -1.0;
  for (int b = 0; b < bins; ++b) {
    double s = 0.0;
    for (int k = -radius; k <= radius; ++k) {
      const double g = sigma_bins > 0.0 ? std::exp(-0.5 * k * k / (sigma_bins * sigma_bins)) : 1.0;
      s += g * hist[((b + k) % bins + bins) % bins];
    }
    if (s > peak_value) {
      peak_value = s;
      peak = b;
    }
  }
  const double peak_angle = (peak + 0.5) * bin;

  // Refine: circular mean of 4*angle (period 90 deg) over the walls near the peak.
  double c = 0.0, s = 0.0, support = 0.0;
  for (size_t i = 0; i < angles.size(); ++i) {
    if (quarterDistance(angles[i], peak_angle) > config.window_deg * kDeg) continue;
    c += w[i] * std::cos(4.0 * angles[i]);
    s += w[i] * std::sin(4.0 * angles[i]);
    support += w[i];
  }
  double yaw = foldQuarter(std::atan2(s, c) / 4.0);
  if (yaw >= kQuarter / 2.0) yaw -= kQuarter;  // into [-45, 45) deg
  axes.yaw = yaw;
  axes.support = support;
  axes.agreement = total > 0.0 ? support / total : 0.0;
  axes.valid = support >= config.min_support;
  if (!axes.valid) axes.yaw = 0.0;
  return axes;
}

DominantAxes estimateDominantAxes(const std::vector<WallSegment>& walls,
                                  const DominantAxesConfig& config) {
  std::vector<Eigen::Vector3d> normals;
  std::vector<double> weights;
  for (const auto& wall : walls) {
    normals.push_back(wall.normal);
    weights.push_back(wall.length());
  }
  return estimateDominantAxes(normals, weights, config);
}

DominantAxes estimateDominantAxes(const WallMap& map, const DominantAxesConfig& config) {
  std::vector<Eigen::Vector3d> normals;
  std::vector<double> weights;
  for (const auto& [id, wall] : map.landmarks()) {
    normals.push_back(wall.normal);
    weights.push_back(wall.length());
  }
  return estimateDominantAxes(normals, weights, config);
}

WallDirection classifyWall(const Eigen::Vector3d& normal, const DominantAxes& axes) {
  const double along_x = normal.head<2>().dot(axes.xAxis());
  const double along_y = normal.head<2>().dot(axes.yAxis());
  if (std::abs(along_x) >= std::abs(along_y)) {
    return along_x >= 0.0 ? WallDirection::kXPlus : WallDirection::kXMinus;
  }
  return along_y >= 0.0 ? WallDirection::kYPlus : WallDirection::kYMinus;
}

const char* toString(WallDirection d) {
  switch (d) {
    case WallDirection::kXPlus:
      return "x+";
    case WallDirection::kXMinus:
      return "x-";
    case WallDirection::kYPlus:
      return "y+";
    case WallDirection::kYMinus:
      return "y-";
  }
  return "?";
}

}  // namespace tacs
