#include "tacs_graphs/rooms/room_bounds.h"

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

namespace tacs {
namespace {

constexpr double kLongWallM = 4.0;  // [m] a wall this long is one of the building's
// A face whose top is below this share of the walls' is of furniture height: half walls, cabinets,
// sideboards (legged_office's 1.2 m one under 2.8 m, open_lobby's 1.1 m half walls under 3.2 m).
constexpr double kFurnitureTopShare = 0.6;

bool meets(const WallLandmark& plane, const WallLandmark& anchored, double distance) {
  return std::any_of(
      std::begin(plane.endpoints), std::end(plane.endpoints), [&](const Eigen::Vector2d& end) {
        return distanceToSegment(end, anchored.endpoints[0], anchored.endpoints[1]) <= distance;
      });
}

// Whether the other face of `plane` is a landmark too: one facing the opposite way, at most
// `max_thickness` behind it, along at least half of the shorter face. A partition or a half wall
// between two rooms is seen from both sides; the front of a cabinet or a sideboard standing in a
// room's corner only from the room (legged_office's 1.2 m sideboard, its end against the west
// wall, split the meeting room in two when it counted as a partition).
bool seenFromBothSides(const WallLandmark& plane, const std::map<uint32_t, WallLandmark>& all,
                       double max_thickness) {
  const Eigen::Vector2d n = plane.normal.head<2>().normalized();
  const Eigen::Vector2d origin = plane.endpoints[0];
  const Eigen::Vector2d axis = (plane.endpoints[1] - origin).normalized();
  constexpr double kOppositeCos = 0.94;  // normals within 20 deg of opposite
  constexpr double kPlaneNoiseM = 0.05;  // a back face estimated a little in front of the front
  return std::any_of(all.begin(), all.end(), [&](const auto& entry) {
    const WallLandmark& other = entry.second;
    if (other.normal.head<2>().normalized().dot(n) > -kOppositeCos) return false;
    const double behind = n.dot(origin - other.midpoint());
    if (behind < -kPlaneNoiseM || behind > max_thickness) return false;
    double b0 = axis.dot(other.endpoints[0] - origin), b1 = axis.dot(other.endpoints[1] - origin);
    if (b0 > b1) std::swap(b0, b1);
    const double overlap = std::min(plane.length(), b1) - std::max(0.0, b0);
    return overlap >= 0.5 * std::min(plane.length(), other.length());
  });
}

}  // namespace

bool freeStandingFurnitureBoundsNoRoom(const RoomsConfig& config) {
  return config.method == RoomMethod::kTacs && config.extraction.anchor_distance > 0.0;
}

std::map<uint32_t, WallLandmark> roomBoundingPlanes(const WallMap& walls,
                                                    const RoomExtractionConfig& config) {
  return roomBoundingPlanes(walls, config.anchor_distance, config.wall_top_margin,
                            config.wall_top_min_share, config.partition_max_thickness);
}

std::map<uint32_t, WallLandmark> roomBoundingPlanes(const WallMap& walls, double anchor_distance,
                                                    double top_margin, double top_min_share,
                                                    double partition_max_thickness) {
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
  // Of furniture height, only a face seen from both sides is a partition that may be anchored.
  // (A wall whose top is seen a little low, as the real hall's 3.7 m jog under its 5 m walls,
  // stays anchored by its end alone.)
  if (partition_max_thickness > 0.0) {
    const double furniture_top = kFurnitureTopShare * tallest;
    loose.erase(std::remove_if(loose.begin(), loose.end(),
                               [&](const auto& entry) {
                                 return entry.second->mean_top < furniture_top &&
                                        !seenFromBothSides(*entry.second, all,
                                                           partition_max_thickness);
                               }),
                loose.end());
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
