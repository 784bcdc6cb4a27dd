// Room segmentation, called once per keyframe (paper Sec. III-B and III-C).
//
//   RoomSegmenter seg(config.rooms, config.walls.axes, T_base_sensor);
//   for each keyframe (after the TraversableMap and the WallMap took it in):
//     RoomSegmentationResult r = seg.processKeyframe(id, T_map_base, trav_map, wall_map, &cloud);
//     for (size_t i = 0; i < r.associations.size(); ++i) {
//       const RoomAssociation& a = r.associations[i];
//       backend.setRoom(seg.rooms().at(a.room_id));          // room / corridor factors
//       for (auto [w_mapped, w_new] : a.wall_to_wall) backend.addWallToWall(w_mapped, w_new);
//       if (!a.created) { /* room re-detected: trigger loop closure (Sec. III-D) */ }
//     }
//   at the end: seg.finish(trav_map, wall_map) (same result type).
//
// method "tacs": TacsFreeSpace gives finished free-space regions (T_room, eq. 3), each goes
// through room extraction (a region no facing pair bounds, around a corridor corner, is tried again
// on its free space within tacs.path_retry_radius of the robot's positions in it) and TACS room
// merging (RoomMap::addObservation).
// method "voxel": the keyframe cloud is integrated into VoxelFreeSpace; every
// update_every_keyframes keyframes all clusters are extracted and associated by centre distance
// (RoomMap::addByCenterDistance), as S-Graphs+ does on a timer; every re-clustering reports each
// cluster again (created = false), so room-triggered loop closure is meant for "tacs" only.
// Walls come from the WallMap (the backend's, so room wall ids are landmark ids); the building
// axes are estimated from it at every call.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tacs_graphs/rooms/room_map.h"
#include "tacs_graphs/rooms/rooms_config.h"
#include "tacs_graphs/rooms/tacs_free_space.h"
#include "tacs_graphs/rooms/voxel_free_space.h"
#include "tacs_graphs/scene_graph/scene_graph.h"
#include "tacs_graphs/traversability/traversable_map.h"
#include "tacs_graphs/walls/dominant_axes.h"
#include "tacs_graphs/walls/wall_map.h"

namespace tacs {

struct RoomSegmentationResult {
  /// Rooms/corridors detected at this call, and what the room map did with each (same order).
  std::vector<RoomObservation> observations;
  std::vector<RoomAssociation> associations;
  /// Free-space regions that gave no room, with the reason (no facing walls, too small, ...).
  std::vector<std::string> rejected;
  /// TACS: the robot stood on a safe node (T_inside not empty); doorways cut in the room graph.
  bool robot_inside = false;
  size_t doorways = 0;
  double time_ms = 0.0;
};

class RoomSegmenter {
 public:
  /// Validates the configs (throws ConfigError). T_base_sensor: ray origin of the voxel method.
  explicit RoomSegmenter(const RoomsConfig& config, const DominantAxesConfig& axes = {},
                         const Pose3& T_base_sensor = Pose3::Identity());

  /// One keyframe. `map` and `walls` must already contain this keyframe; T_map_base is its
  /// (optimised) pose with base_link on the floor. `cloud_in_base` (the keyframe cloud in the
  /// base frame) is needed by the voxel method only and may be null for "tacs".
  RoomSegmentationResult processKeyframe(uint32_t keyframe_id, const Pose3& T_map_base,
                                         const TraversableMap& map, const WallMap& walls,
                                         const PointCloud* cloud_in_base = nullptr);

  /// End of the sequence: emits the region still being accumulated (tacs) or runs a last
  /// clustering (voxel).
  RoomSegmentationResult finish(const TraversableMap& map, const WallMap& walls);

  /// The mapped rooms (id -> room), for the backend and the scene graph.
  const std::map<uint32_t, MappedRoom>& rooms() const { return room_map_.rooms(); }
  /// Writes every room as a RoomNode into `graph` and sets the room_id of their keyframes that
  /// the graph holds.
  void writeTo(SceneGraph* graph) const;

  const RoomsConfig& config() const { return config_; }

 private:
  /// `path`: the robot's positions in the region (TACS; empty for voxel clusters).
  void addRegion(std::vector<Eigen::Vector3d> points, std::vector<uint32_t> keyframe_ids,
                 const std::vector<Eigen::Vector3d>& path, const WallMap& walls,
                 const DominantAxes& axes, RoomSegmentationResult* result);
  void clusterVoxels(const WallMap& walls, const DominantAxes& axes,
                     RoomSegmentationResult* result);
  /// A corridor wider than rooms.extraction.max_corridor_width_m that free-standing furniture
  /// closes on its other axis (its region `points`) joins the mapped hall sharing one of its
  /// walls; true when it did.
  bool joinedAHall(const RoomExtractionResult& extracted,
                   const std::vector<Eigen::Vector3d>& points,
                   const std::vector<uint32_t>& keyframe_ids, const WallMap& walls,
                   const std::map<uint32_t, WallLandmark>& bounding,
                   const std::vector<Doorway>& bounding_doorways, const DominantAxes& axes,
                   RoomSegmentationResult* result);
  /// Joins the kept regions that only free-standing furniture bounds to the rooms they open into
  /// (RoomMap::addUnbounded), once such a room is mapped.
  /// `bounding`: the planes that may bound rooms (rooms/room_bounds.h).
  void joinUnboundedRegions(const WallMap& walls, const std::map<uint32_t, WallLandmark>& bounding,
                            const std::vector<Doorway>& bounding_doorways,
                            RoomSegmentationResult* result);

  RoomsConfig config_;
  DominantAxesConfig axes_config_;
  Pose3 T_base_sensor_;
  TacsFreeSpace tacs_;
  VoxelFreeSpace voxel_;
  RoomMap room_map_;
  std::vector<RoomObservation> unbounded_;  // regions waiting for the room they open into
  int keyframes_since_clustering_ = 0;
};

}  // namespace tacs
