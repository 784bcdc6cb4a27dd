#include "tacs_graphs/rooms/room_bounds.h"

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

namespace tacs {
namespace {

constexpr double kLongWallM = 4.0;  // [m] a wall this long is one of the building's

bool meets(const WallLandmark& plane, const WallLandmark& anchored, double distance) {
  return std::any_of(
      std::begin(plane.endpoints), std::end(plane.endpoints), [&](const Eigen::Vector2d& end) {
        return distanceToSegment(end, anchored.endpoints[0], anchored.endpoints[1]) <= distance;
      });
}

}  // namespace

bool freeStandingFurnitureBoundsNoRoom(const RoomsConfig& config) {
  return config.method == RoomMethod::kTacs && config.extraction.anchor_distance > 0.0;
}

std::map<uint32_t, WallLandmark> roomBoundingPlanes(const WallMap& walls,
                                                    const RoomExtractionConfig& config) {
  return roomBoundingPlanes(walls, config.anchor_distance, config.wall_top_margin,
                            config.wall_top_min_share);
}

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
  constexpr double kNone = -std::numeric_limits<double>::infinity();
  double tallest_any = kNone, tallest_long = kNone;
  for (const auto& [id, plane] : all) {
    if (walls.hasWallShape(id)) {
      shaped.emplace_back(id, &plane);
      tallest_any = std::max(tallest_any, plane.mean_top);
      if (plane.length() >= kLongWallM) tallest_long = std::max(tallest_long, plane.mean_top);
    } else {
      loose.emplace_back(id, &plane);
    }
  }
  const double tallest = tallest_long > kNone ? tallest_long : tallest_any;
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
