// The backend: owner of the scene graph (docs/DESIGN.md). It turns keyframes, wall observations,
// room observations and loop closures into factor-graph measurements, associates walls to
// landmarks, optimises on schedule and exports the optimised scene graph and the map->odom
// correction.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "tacs_graphs/backend/factor_graph.h"
#include "tacs_graphs/rooms/room_map.h"
#include "tacs_graphs/scene_graph/scene_graph.h"
#include "tacs_graphs/walls/wall_map.h"

namespace tacs {

class Backend {
 public:
  using Matrix6d = Eigen::Matrix<double, 6, 6>;

  Backend(const BackendConfig& config, const WallAssociationConfig& association);

  /// A keyframe from the odometry: its odom-frame pose and the information of the motion since the
  /// previous keyframe. Its map pose starts from the current map->odom correction.
  void addKeyframe(uint32_t id, double stamp, const Pose3& T_odom_base,
                   const Matrix6d& information);
  bool hasKeyframe(uint32_t id) const { return keyframes_.count(id) > 0; }
  size_t keyframeCount() const { return keyframes_.size(); }

  /// Walls seen from keyframe `id` (base frame). Returns the landmark id of each observation.
  /// `seen_over` are the surfaces the extractor saw over (WallExtractionResult::seen_over): the
  /// wall map remembers them, and landmarks lying on them are no walls (WallNode::is_wall).
  std::vector<uint32_t> addWallObservations(uint32_t keyframe_id,
                                            const std::vector<WallSegment>& walls,
                                            const std::vector<WallSegment>& seen_over = {});

  /// A loop closure: the pose of keyframe `to` in the frame of keyframe `from`.
  void addLoopClosure(uint32_t from, uint32_t to, const Pose3& T_from_to,
                      const Matrix6d& information, double score);

  /// Adds or updates a room from the room segmenter (RoomSegmenter::rooms()): one RoomPairFactor
  /// per facing wall pair (two for a four-wall room, one for a corridor) and, for a corridor, a
  /// CorridorAnchorFactor to the centre of its free space. Wall ids are landmark ids of
  /// wallMap(); pairs on walls the graph does not hold are skipped. Returns false (and stores
  /// nothing) when no pair is left. Free space and keyframes go into sceneGraph().
  bool setRoom(const MappedRoom& room);
  /// Removes a room and its factors (a room merged into another by room merging).
  void removeRoom(uint32_t id);
  /// Wall-to-wall edge of room merging (paper eq. 4) between two wall landmarks; returns false
  /// when a wall is unknown, both ids are the same or the edge exists already.
  bool addWallToWall(uint32_t wall_a, uint32_t wall_b);

  /// Optimises when the schedule says so (every `optimize_every_keyframes` keyframes, and after a
  /// loop closure): a full solve, or with backend.window_keyframes a window solve between full
  /// ones. Returns the report of the optimisation, if one ran.
  std::optional<OptimizationReport> optimizeIfDue();
  /// Optimises the whole graph now, then folds duplicate walls.
  OptimizationReport optimize();

  size_t roomCount() const { return rooms_.size(); }

  /// Optimised pose of a keyframe in the map frame.
  Pose3 keyframePose(uint32_t id) const { return graph_.keyframePose(id); }
  /// Its position alone (no rotation built: keyframe retention asks for many per keyframe).
  Eigen::Vector3d keyframePosition(uint32_t id) const { return graph_.keyframePosition(id); }
  /// T_map_odom from the latest keyframe.
  Pose3 mapToOdom() const;
  /// Keyframes, wall landmarks (WallNode::is_wall from WallMap::isWall()), rooms (optimised
  /// centres, free space, keyframes; keyframes get the room_id of the room listing them) and
  /// loops.
  SceneGraph sceneGraph() const;
  const WallMap& wallMap() const { return wall_map_; }
  /// Total optimisation time so far (t_FGO) and the number of optimisations.
  double totalOptimizationMs() const { return total_optimization_ms_; }
  /// Its CPU time: t_FGO less the time the backend waited for a core.
  double totalOptimizationCpuMs() const { return total_optimization_cpu_ms_; }
  int optimizations() const { return optimizations_; }

 private:
  struct KeyframeInfo {
    double stamp;
    Pose3 T_odom_base;
  };

  /// One optimisation (0: full; else a window of that many keyframes), then the landmarks follow.
  OptimizationReport run(size_t window_keyframes);
  void renameRoomWall(uint32_t removed, uint32_t kept);
  void writeRooms(SceneGraph* graph) const;

  BackendConfig config_;
  FactorGraph graph_;
  std::map<uint32_t, RoomNode> rooms_;
  std::set<std::pair<uint32_t, uint32_t>> wall_to_wall_;  // edges added (smaller id first)
  WallMap wall_map_;
  std::map<uint32_t, KeyframeInfo> keyframes_;
  std::optional<uint32_t> last_keyframe_;
  std::vector<LoopEdge> loops_;
  int keyframes_since_optimization_ = 0;
  size_t keyframes_since_full_solve_ = 0;
  bool loop_pending_ = false;
  double total_optimization_ms_ = 0.0;
  double total_optimization_cpu_ms_ = 0.0;
  int optimizations_ = 0;
};

}  // namespace tacs
