// The hierarchical scene graph: keyframes, walls, rooms/corridors and loop edges, all in the map
// frame. The backend owns it; JSON is the run-folder format of docs/DESIGN.md ("scene_graph.json").
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tacs_graphs/common/types.h"

namespace tacs {

struct KeyframeNode {
  uint32_t id = 0;
  double stamp = 0.0;
  // Stored as translation + quaternion so that JSON round-trips exactly.
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  int room_id = -1;  // -1: in no room

  Pose3 pose() const;
  void setPose(const Pose3& T_map_base);
};

/// A wall: the plane {p : normal . p + d = 0} facing the room it was seen from.
struct WallNode {
  uint32_t id = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  double d = 0.0;
  std::array<Eigen::Vector2d, 2> endpoints = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  std::array<double, 2> z_range = {0.0, 0.0};
  /// False for a plane landmark that is no wall of the building: a surface the sensor saw over
  /// (cabinet, shelf, half wall), one shorter than a wall (pillar face, box side), or, with the
  /// paper's rooms, free-standing furniture of less than a wall's height (rack row, book stack,
  /// cubicle partition). It still constrains the poses, and bounds a room when it is anchored to
  /// the walls (rooms/room_bounds.h).
  bool is_wall = true;
};

enum class RoomKind { kRoom, kCorridor };
const char* roomKindName(RoomKind kind);

struct RoomNode {
  uint32_t id = 0;
  RoomKind kind = RoomKind::kRoom;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  std::vector<uint32_t> wall_ids;
  std::vector<Eigen::Vector2d> free_space;  // map-frame xy of the room's traversable nodes
  std::vector<uint32_t> keyframe_ids;
};

struct LoopEdge {
  uint32_t from = 0;
  uint32_t to = 0;
  // Pose of keyframe `to` in the frame of keyframe `from`.
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  double score = 0.0;

  Pose3 relativePose() const;
};

/// The scans a live graph was built from: a suite that falls behind maps fewer scans.
struct ScanInput {
  uint64_t scans_received = 0;
  uint64_t scans_missing = 0;
  double dropRatio() const {
    const uint64_t produced = scans_received + scans_missing;
    return produced == 0 ? 0.0 : static_cast<double>(scans_missing) / produced;
  }
};

struct SceneGraph {
  std::map<uint32_t, KeyframeNode> keyframes;
  std::map<uint32_t, WallNode> walls;
  std::map<uint32_t, RoomNode> rooms;
  std::vector<LoopEdge> loops;
  /// Set by the live backend ("input" in the JSON); absent offline.
  std::optional<ScanInput> input;

  /// Wall nodes that are walls of the building (WallNode::is_wall), not other planes.
  size_t wallCount() const;
  /// The graph moved into another map frame: T_new_map applied to every pose, plane, wall end and
  /// room (2D parts by its yaw and xy shift: the frames share gravity). Loops are relative.
  SceneGraph transformed(const Pose3& T_new_map) const;

  nlohmann::json toJson() const;
  /// Throws std::runtime_error naming the bad field ("rooms[2].kind: ...").
  static SceneGraph fromJson(const nlohmann::json& j);

  /// Writes the JSON atomically (a crash never leaves a half-written file).
  void save(const std::string& path) const;
  static SceneGraph load(const std::string& path);
};

}  // namespace tacs
