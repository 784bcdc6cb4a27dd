// Room extraction (paper Sec. III-B-3): from a free-space region (the room-level traversable graph
// T_room of eq. 3, or a voxel cluster) and the wall landmarks, the walls that bound the region.
//
// Walls are sorted into x+/x-/y+/y- by their normal along the building's dominant axes (a wall
// seen from inside a room faces the room). A free-space point is adjacent to a wall when it lies
// in front of it (on the side its normal faces) within `adjacency_distance`, and along the wall
// within its extent +- `extent_margin`. For each category the wall with most adjacent points is
// chosen; two facing walls (x+ below x-, or y+ below y-, at least `min_width` apart, with most of
// the region between them) form a pair. Two pairs make a four-wall room, one pair a corridor
// running along its walls. When the best walls of a category do not form a valid pair, the
// best-scoring valid pair among the candidates is taken (the paper's rule whenever it is valid).
// The centre is midway between the bounding walls; for a corridor, along its walls it is the
// mean of the free space between them.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "tacs_graphs/rooms/rooms_config.h"
#include "tacs_graphs/rooms/tacs_free_space.h"
#include "tacs_graphs/scene_graph/scene_graph.h"
#include "tacs_graphs/walls/dominant_axes.h"
#include "tacs_graphs/walls/wall_map.h"

namespace tacs {

/// One detection of a room or corridor (a RoomObservation is what the segmenter emits; the room
/// map folds observations of one room into a mapped room of the same type).
struct RoomObservation {
  RoomKind kind = RoomKind::kRoom;
  /// Wall landmark id per category, indexed by WallDirection (x+, x-, y+, y-); -1 when absent.
  /// A four-wall room has all four; a corridor has one facing pair.
  std::array<int, 4> walls = {-1, -1, -1, -1};
  /// Centre in the map frame (z: mean height of the free space) [m].
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  /// Yaw of the building x axis used to classify the walls [rad].
  double axes_yaw = 0.0;
  /// Map-frame positions of the free-space nodes (T_room of eq. 3, or voxel cells).
  std::vector<Eigen::Vector3d> free_space;
  /// Keyframes recorded while the robot was inside the region.
  std::vector<uint32_t> keyframe_ids;

  bool hasXPair() const { return walls[0] >= 0 && walls[1] >= 0; }
  bool hasYPair() const { return walls[2] >= 0 && walls[3] >= 0; }
  /// Facing wall pairs (x+, x-) and/or (y+, y-): the RoomPairFactor pairs of the backend.
  std::vector<std::pair<uint32_t, uint32_t>> wallPairs() const;
  /// All wall ids, in x+, x-, y+, y- order.
  std::vector<uint32_t> wallIds() const;
  /// Building axes of this room (x axis at axes_yaw).
  Eigen::Vector2d xAxis() const;
  Eigen::Vector2d yAxis() const;
  /// Mean xy of the free space.
  Eigen::Vector2d freeSpaceCentroid() const;
};

struct RoomExtractionResult {
  bool found = false;
  RoomObservation room;  // valid when found
  /// Adjacent free-space points of the chosen wall per category (0 when none).
  std::array<int, 4> adjacent_points = {0, 0, 0, 0};
  /// A corridor's width: the distance of its facing pair (0 for a four-wall room) [m].
  double corridor_width = 0.0;
  /// Why no room was found (empty when found).
  std::string reason;
};

/// Extracts the room bounded by `landmarks` around `free_space` (map frame). The observation's
/// free_space is the input, less what lies behind the room's walls (`outside_margin`); a wall
/// runs on across the `doorways` (rooms/tacs_free_space.h) beside it. keyframe_ids are left
/// empty for the caller.
RoomExtractionResult extractRoom(const std::vector<Eigen::Vector3d>& free_space,
                                 const std::map<uint32_t, WallLandmark>& landmarks,
                                 const DominantAxes& axes, const RoomExtractionConfig& config,
                                 const std::vector<Doorway>& doorways = {});

/// Recomputes the centre of a room from its walls' current planes and its free space (after the
/// backend moved the walls, or after free space was merged in). Walls missing from `landmarks`
/// keep the centre's previous coordinate along their axis.
void recomputeRoomCenter(const std::map<uint32_t, WallLandmark>& landmarks, RoomObservation* room);

}  // namespace tacs
