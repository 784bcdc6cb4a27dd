#include "tacs_graphs/eval/wall_metrics.h"

#include <algorithm>
#include <cmath>

namespace tacs {
namespace {

// Does the estimated segment a-b (with unit normal n) lie on one face of the wall?
bool liesOn(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& n,
            const sim::Wall& wall, const WallMetricsConfig& c) {
  const Eigen::Vector2d along = wall.to - wall.from;
  const double length = along.norm();
  if (length <= 0.0) return false;
  const Eigen::Vector2d u = along / length;
  const Eigen::Vector2d wall_normal(-u.y(), u.x());
  if (std::abs(wall_normal.dot(n)) < std::cos(c.max_angle_deg * M_PI / 180.0)) return false;
  for (const double side : {-0.5, 0.5}) {  // the two faces of the wall box
    const Eigen::Vector2d origin = wall.from + side * wall.thickness * wall_normal;
    const auto offset = [&](const Eigen::Vector2d& p) { return (p - origin).dot(wall_normal); };
    if (std::abs(offset(a)) > c.max_distance || std::abs(offset(b)) > c.max_distance) continue;
    const double s0 = std::min((a - origin).dot(u), (b - origin).dot(u));
    const double s1 = std::max((a - origin).dot(u), (b - origin).dot(u));
    // The face spans the wall's length plus half its thickness at each end (as the box does).
    const double lo = -0.5 * wall.thickness, hi = length + 0.5 * wall.thickness;
    const double overlap = std::max(0.0, std::min(s1, hi) - std::max(s0, lo));
    if (s1 - s0 > 0.0 && overlap >= c.min_overlap * (s1 - s0)) return true;
  }
  return false;
}

}  // namespace

WallMetrics evaluateWalls(const SceneGraph& graph, const std::vector<sim::Wall>& ground_truth,
                          const WallMetricsConfig& config) {
  WallMetrics m;
  for (const auto& [id, w] : graph.walls) {
    if (!w.is_wall) continue;
    ++m.walls;
    const Eigen::Vector2d n = w.normal.head<2>().normalized();
    const bool correct = std::any_of(ground_truth.begin(), ground_truth.end(), [&](const auto& g) {
      return liesOn(w.endpoints[0], w.endpoints[1], n, g, config);
    });
    m.correct += correct ? 1 : 0;
  }
  return m;
}

}  // namespace tacs
