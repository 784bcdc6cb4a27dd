// What the backend node keeps around the core Backend, without ROS: keyframe clouds for the map,
// wall observations and loop closures that arrive before their keyframes (buffered by keyframe
// id), room nodes from room observations, the saved products of a run and the measurement
// journal that lets a restarted backend recover the graph.
//
// Rooms come already associated (room merging runs in room_segmentation, paper Sec. III-C): each
// is a mapped room with its id, and goes to Backend::setRoom with its wall-to-wall edges (eq. 4).
#pragma once

#include <deque>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "tacs_graphs/backend/backend.h"
#include "tacs_graphs/backend/map_export.h"
#include "tacs_graphs/loop_closure/loop_detector.h"
#include "tacs_graphs/pipeline/pipeline_config.h"

namespace tacs {

/// What the wall extraction reported for one keyframe (base frame).
struct KeyframeWalls {
  std::vector<WallSegment> walls;
  /// Surfaces seen over (WallExtractionResult::seen_over).
  std::vector<WallSegment> seen_over;
};

struct BackendSessionOptions {
  size_t max_pending_keyframes = 300;  // wall/loop messages waiting for this many keyframes at most
  /// Keep the measurement journal (journal(), save(), recover()): the backend node's crash
  /// safety. The offline pipeline, which never restarts, keeps none.
  bool keep_journal = true;
};

class BackendSession {
 public:
  using Matrix6d = Eigen::Matrix<double, 6, 6>;
  enum class Outcome { kAdded, kBuffered, kDuplicate, kDropped };

  BackendSession(const PipelineConfig& config, const BackendSessionOptions& options);

  /// Adds a keyframe and then any walls and loops that were waiting for it.
  Outcome addKeyframe(uint32_t id, double stamp, const Pose3& T_odom_base,
                      const Matrix6d& information, const PointCloud::ConstPtr& cloud);
  /// Walls of keyframe `id` (base frame); buffered when the keyframe has not arrived yet. A
  /// second message for a keyframe whose walls were taken is a duplicate (a resent keyframe).
  Outcome addWalls(uint32_t keyframe_id, const KeyframeWalls& walls);
  /// A loop closure; buffered until both keyframes are known. A pair already closed is a
  /// duplicate (loops republished after a restart).
  Outcome addLoop(const LoopEdge& edge, const Matrix6d& information);
  /// The same for a loop as the detector reports it.
  Outcome addLoop(const LoopClosure& loop);
  /// A mapped room (map frame, wall ids of this backend's landmarks) and the wall-to-wall edges
  /// (mapped wall, observed wall) of its merging. Returns false when the backend holds none of
  /// its facing wall pairs (nothing stored; the next update of the room tries again).
  bool setRoom(const MappedRoom& room,
               const std::vector<std::pair<uint32_t, uint32_t>>& wall_to_wall = {});
  /// Removes a room merged into another (RoomAssociation::absorbed), from the graph and journal.
  void removeRoom(uint32_t id);
  /// A room update of room segmentation: the rooms merged into `room` leave the graph (even when
  /// `room` itself cannot be stored yet), then setRoom. Returns setRoom's answer.
  bool takeRoom(const MappedRoom& room, const std::vector<uint32_t>& absorbed,
                const std::vector<std::pair<uint32_t, uint32_t>>& wall_to_wall);
  /// Removes every room not in `ids` (the room segmenter's complete set). Returns how many.
  size_t retainRooms(const std::set<uint32_t>& ids);
  size_t roomCount() const { return backend_.roomCount(); }

  std::optional<OptimizationReport> optimizeIfDue() { return backend_.optimizeIfDue(); }
  OptimizationReport optimize() { return backend_.optimize(); }
  /// The sensor's position in the base frame (the keyframes' sensor_origin): map.bt's rays
  /// start there. Until a keyframe says otherwise, frames.base_to_sensor.
  void noteSensorInBase(const Eigen::Vector3d& sensor_in_base) { sensor_in_base_ = sensor_in_base; }

  /// The optimised scene graph with the room nodes, the keyframes' room ids and the scan input.
  /// With the paper's rooms (rooms.method tacs), a plane that bounds no room because it is
  /// free-standing furniture (rooms/room_bounds.h: a rack row, a book stack, a cubicle
  /// partition) is no wall of the graph either (WallNode::is_wall).
  SceneGraph sceneGraph() const;
  /// The odometry's scan counts (from its keyframes); the largest seen are kept.
  void noteScanInput(const ScanInput& input);
  const std::optional<ScanInput>& scanInput() const { return scan_input_; }
  Pose3 mapToOdom() const { return backend_.mapToOdom(); }
  const Backend& backend() const { return backend_; }
  const KeyframeClouds& keyframeClouds() const { return clouds_.clouds(); }
  std::map<uint32_t, uint32_t> wallObservationCounts() const;
  size_t keyframeCount() const { return backend_.keyframeCount(); }
  /// The highest keyframe id taken (0 before the first).
  uint32_t newestKeyframe() const { return newest_keyframe_; }
  size_t pendingCount() const;
  /// The first keyframe this session still misses something of after a restart: the oldest
  /// recent keyframe without its walls, else the one after the newest.
  uint32_t firstIncompleteKeyframe() const;
  /// Ids below the newest that never arrived (gaps in the odometry's numbering).
  std::vector<uint32_t> missingKeyframes() const;

  /// Map cloud (map frame): keyframe clouds at optimised poses plus a recovered map, if any.
  PointCloud mapCloud(double voxel_m) const;

  /// Writes scene_graph.json, trajectory_tum.txt (keyframes at their optimised poses), map.pcd,
  /// map.bt and backend_journal.json into `dir` (created if
  /// needed), each atomically, and run.json: status "saving" first, "complete" last, with the
  /// keyframe count, the keyframe ids that never arrived and the scan counts. Throws
  /// std::runtime_error.
  void save(const std::string& dir, const MapExportConfig& map_config) const;

  /// Replays backend_journal.json of `dir` (and loads map.pcd as a fixed part of the map).
  /// Returns the number of keyframes recovered. Throws std::runtime_error naming the file.
  size_t recover(const std::string& dir);

  /// The measurements received so far (keyframes, walls, loops, rooms) as JSON.
  nlohmann::json journal() const;
  /// The same as JSON text, composed without building the tree (what save() writes).
  std::string journalText() const;

 private:
  void flushPending(uint32_t keyframe_id);
  nlohmann::json runStatus(const std::string& status) const;
  void dropStalePending();

  PipelineConfig config_;
  BackendSessionOptions options_;
  Backend backend_;
  std::optional<ScanInput> scan_input_;
  MapClouds clouds_;
  Eigen::Vector3d sensor_in_base_;  // map.bt's ray origin (noteSensorInBase)
  PointCloud::Ptr recovered_map_;
  std::map<uint32_t, KeyframeWalls> pending_walls_;
  std::vector<std::pair<LoopEdge, Matrix6d>> pending_loops_;
  std::map<uint32_t, nlohmann::json> journal_rooms_;  // latest version of each room, by id
  std::map<uint32_t, std::set<std::pair<uint32_t, uint32_t>>> wall_to_wall_;  // by room id
  std::set<uint32_t> walls_taken_;  // keyframes whose walls were added (even none)
  std::set<std::pair<uint32_t, uint32_t>> loops_taken_;
  uint32_t newest_keyframe_ = 0;
  // Entries kept as compact JSON text: a parsed nlohmann::json tree takes about ten times the
  // memory, and the journal grows with every keyframe.
  std::vector<std::string> journal_keyframes_;
  std::vector<std::string> journal_walls_;
  std::vector<std::string> journal_loops_;
};

}  // namespace tacs
