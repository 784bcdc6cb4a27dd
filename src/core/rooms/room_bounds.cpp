#include "tacs_graphs/rooms/room_bounds.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace tacs {
namespace {

constexpr double kLongWallM = 4.0;  // [m] a wall this long is one of the building's

// Distance (xy) from p to the segment a-b.
double distanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

bool meets(const WallLandmark& plane, const WallLandmark& anchored, double distance) {
  return std::any_of(
      std::begin(plane.endpoints), std::end(plane.endpoints), [&](const Eigen::Vector2d& end) {
        return distanceToSegment(end, anchored.endpoints[0], anchored.endpoints[1]) <= distance;
      });
}

}  // namespace

std::map<uint32_t, WallLandmark> roomBoundingPlanes(const WallMap& walls, double anchor_distance,
                                                    double top_margin, double top_min_share) {
  const std::map<uint32_t, WallLandmark>& all = walls.landmarks();
  if (anchor_distance <= 0.0) return all;
  // Rack faces seen only from their aisle are never seen over, so they pass for walls by their
  // shape; their top, far below the hall's walls, gives them away. (hasWallShape scans the other
  // landmarks: asked once per plane.)
  std::vector<std::pair<uint32_t, const WallLandmark*>> shaped, loose;  // loose: not anchored yet
  // The walls' top is the tallest long wall's: a column face or a short plane up a high ceiling
  // (the real hall's 2 m face reaching 8 m, its 40 m walls 5 m) would put every wall below it.
  double tallest = -std::numeric_limits<double>::infinity();
  double tallest_long = tallest;
  for (const auto& [id, plane] : all) {
    if (walls.hasWallShape(id)) {
      shaped.emplace_back(id, &plane);
      tallest = std::max(tallest, plane.mean_top);
      if (plane.length() >= kLongWallM) tallest_long = std::max(tallest_long, plane.mean_top);
    } else {
      loose.emplace_back(id, &plane);
    }
  }
  if (std::isfinite(tallest_long)) tallest = tallest_long;
  std::map<uint32_t, WallLandmark> bounding;
  const double wall_top = std::max(tallest - top_margin, top_min_share * tallest);
  for (const auto& [id, plane] : shaped) {
    if (plane->mean_top >= wall_top) {
      bounding.emplace(id, *plane);
    } else {
      loose.emplace_back(id, plane);
    }
  }
  // Anchoring spreads along chains of planes (partition -> partition -> wall): repeat until no
  // loose plane meets an anchored one.
  for (bool grew = true; grew;) {
    grew = false;
    for (auto it = loose.begin(); it != loose.end();) {
      const WallLandmark& plane = *it->second;
      const bool anchored = std::any_of(bounding.begin(), bounding.end(), [&](const auto& entry) {
        return meets(plane, entry.second, anchor_distance);
      });
      if (anchored) {
        bounding.emplace(it->first, plane);
        it = loose.erase(it);
        grew = true;
      } else {
        ++it;
      }
    }
  }
  return bounding;
}

}  // namespace tacs
