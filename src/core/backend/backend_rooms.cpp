// Rooms in the backend: room / corridor factors from the room segmenter and the wall-to-wall
// edges of room merging (paper Sec. III-B-3, III-C, eq. 4).
#include <algorithm>
#include <optional>

#include "tacs_graphs/backend/backend.h"

namespace tacs {

bool Backend::setRoom(const MappedRoom& room) {
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  for (const auto& [a, b] : room.room.wallPairs()) {
    if (graph_.hasWall(a) && graph_.hasWall(b)) pairs.emplace_back(a, b);
  }
  if (pairs.empty()) return false;
  // A corridor (one pair) is only defined across its walls; along them the free-space centre
  // anchors it.
  std::optional<Eigen::Vector2d> anchor;
  if (pairs.size() == 1) anchor = room.room.freeSpaceCentroid();
  graph_.setRoom(room.id, room.room.center.head<2>(), pairs, anchor);
  RoomNode node = room.toNode();
  node.wall_ids.clear();
  for (const auto& [a, b] : pairs) {
    node.wall_ids.push_back(a);
    node.wall_ids.push_back(b);
  }
  node.kind = pairs.size() == 2 ? RoomKind::kRoom : RoomKind::kCorridor;
  rooms_[room.id] = std::move(node);
  return true;
}

void Backend::removeRoom(uint32_t id) {
  graph_.removeRoom(id);
  rooms_.erase(id);
}

bool Backend::addWallToWall(uint32_t wall_a, uint32_t wall_b) {
  if (wall_a == wall_b || !graph_.hasWall(wall_a) || !graph_.hasWall(wall_b)) return false;
  if (!wall_to_wall_.emplace(std::min(wall_a, wall_b), std::max(wall_a, wall_b)).second) {
    return false;  // every re-detection of a merged room reports its pairs again
  }
  graph_.addWallToWall(wall_a, wall_b);
  return true;
}

void Backend::renameRoomWall(uint32_t removed, uint32_t kept) {
  for (auto& [id, room] : rooms_) {
    for (auto& w : room.wall_ids) {
      if (w == removed) w = kept;
    }
  }
}

void Backend::writeRooms(SceneGraph* graph) const {
  for (const auto& [id, room] : rooms_) {
    RoomNode node = room;
    const Eigen::Vector2d c = graph_.roomCenter(id);
    node.center.x() = c.x();
    node.center.y() = c.y();
    for (uint32_t kf : node.keyframe_ids) {
      auto it = graph->keyframes.find(kf);
      if (it != graph->keyframes.end()) it->second.room_id = static_cast<int>(id);
    }
    graph->rooms[id] = std::move(node);
  }
}

}  // namespace tacs
