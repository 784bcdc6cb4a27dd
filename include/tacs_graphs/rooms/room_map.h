// The map of rooms and the room merging module (paper Sec. III-C).
//
// TACS merging (addObservation): a new observation is the same room as a mapped one when their
// free spaces overlap (share of the smaller one's cells at `overlap_cell`) and their centres are
// close along the axes orthogonal to the walls both define (d(x) = |x_k - x~_k| for two
// y-direction corridors, both axes for two four-wall rooms). Observations bounded by the same
// walls (one landmark, or landmarks of one plane when the views touch or are corridors with no
// wall between them) on every axis both define also merge without overlap (a long corridor or a
// hall walked in separate pieces), and so does a view lying almost entirely inside a mapped room
// (`nested_overlap`, a first partial view), or sharing `open_overlap` of it with no wall between
// the centres (two legs of an L-shaped open floor). Perpendicular corridors, which share no axis,
// merge only when each lies within the other's wall pair (the strips of floor around a large
// table: together a four-wall room); crossing corridors reach beyond each other's walls. Mapped
// rooms merge with each other by the same nesting rule when, after an observation grew one of them,
// the smaller lies almost entirely inside the larger (both views of one hall grew towards each
// other); the larger keeps its id. The mapped room takes over the observation's free space and
// keyframes, adopts a wall pair it lacked (a corridor re-detected as a four-wall room becomes a
// room), and every wall of the observation that differs from the mapped room's wall of the same
// category but lies within max_axis_distance of its plane (two landmarks of one wall) is returned
// as a wall-to-wall pair (eq. 4) for the backend; where the walls of a pair are different walls,
// the view with more free space gives the room its walls.
//
// Baseline merging (addByCenterDistance, S-Graphs+): the nearest mapped room within a fixed 2D
// centre distance, whatever the free space; the room's region becomes the latest cluster.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <unordered_set>
#include <utility>
#include <vector>

#include "tacs_graphs/rooms/room_extraction.h"
#include "tacs_graphs/rooms/rooms_config.h"

namespace tacs {

struct MappedRoom {
  uint32_t id = 0;
  /// Kind, walls, centre, free space (union of the merged observations) and keyframes.
  RoomObservation room;
  /// Observations merged into this room (1 for a room seen once).
  uint32_t observations = 0;
  /// Occupied cells of the free space at merging.overlap_cell (for the overlap test).
  std::unordered_set<int64_t> cells;

  /// The scene-graph node (free_space as map xy).
  RoomNode toNode() const;
};

struct RoomAssociation {
  uint32_t room_id = 0;
  /// True when the observation started a new room; false when it was associated to (merged
  /// into) an existing one, which is the re-detection that triggers loop closure (Sec. III-D).
  bool created = true;
  /// (wall of the mapped room, wall of the observation) of the same category that differ: the
  /// wall-to-wall edges of eq. 4.
  std::vector<std::pair<uint32_t, uint32_t>> wall_to_wall;
  /// Mapped rooms merged into room_id because one came to lie inside the other as both grew
  /// (a hall first seen as a strip along one side): they no longer exist.
  std::vector<uint32_t> absorbed;
};

class RoomMap {
 public:
  /// Validates the config (throws ConfigError).
  explicit RoomMap(const RoomMergingConfig& config = {});

  /// TACS room merging; `landmarks` give the current wall planes for the merged room's centre,
  /// `bounding` (default: `landmarks`) the planes that may stand between two views of a room
  /// (free-standing furniture does not, rooms/room_bounds.h).
  RoomAssociation addObservation(const RoomObservation& observation,
                                 const std::map<uint32_t, WallLandmark>& landmarks,
                                 const std::map<uint32_t, WallLandmark>* bounding = nullptr);

  /// A free-space region only free-standing furniture bounds (an aisle between racks, whose faces
  /// bound no room: rooms/room_bounds.h) joins the mapped room it touches along most cells (at
  /// least 3 cells of merging.overlap_cell in or next to the room's) among those whose wall
  /// pairs enclose 80 % of it, or that share a wall with it (the same face:
  /// `region.walls`, a hall's side beside its gondola rows, where an L-shaped hall's pairs enclose
  /// little) with none of the `bounding` planes (walls and anchored planes, rooms/room_bounds.h)
  /// between the two free spaces' centroids (a room behind the hall's long wall shares it too): its
  /// free space and keyframes become the room's, the room keeps its walls. A region with walls of
  /// its own joins four-wall rooms only. Nothing when no room qualifies. Either way no `bounding`
  /// plane and none of the `doorways` (between bounding planes) may stand between the region's
  /// and the room's free-space centroids: what the room reaches only through its door is not it.
  std::optional<RoomAssociation> addUnbounded(const RoomObservation& region,
                                              const std::map<uint32_t, WallLandmark>& landmarks,
                                              const std::map<uint32_t, WallLandmark>& bounding,
                                              const std::vector<Doorway>& doorways = {});

  /// S-Graphs+ style association by 2D centre distance (the voxel baseline).
  RoomAssociation addByCenterDistance(const RoomObservation& observation,
                                      const std::map<uint32_t, WallLandmark>& landmarks,
                                      double max_distance);

  /// Follows the wall map: a room wall whose landmark disappeared (folded into another) takes
  /// the landmark of the same facing whose plane passes within 0.3 m of the old wall's middle;
  /// then every centre is recomputed from the current planes.
  void refreshWalls(const std::map<uint32_t, WallLandmark>& landmarks);

  const std::map<uint32_t, MappedRoom>& rooms() const { return rooms_; }

  /// True when two mapped rooms with a wall between their centres both lie inside the
  /// observation's free space (nested_overlap of each): a region that ran through a doorway
  /// unnoticed, which merging would fold into one room.
  bool spansSeparateRooms(const RoomObservation& observation,
                          const std::map<uint32_t, WallLandmark>& landmarks) const;

  /// Centre distance between two rooms along the axes both define (the axes orthogonal to their
  /// wall pairs); negative when they share no axis.
  static double axisDistance(const RoomObservation& a, const RoomObservation& b);
  void clear();

 private:
  struct WallMemo {
    Eigen::Vector3d normal;
    Eigen::Vector2d midpoint;
  };
  uint32_t create(const RoomObservation& observation);
  /// Whether two views sharing `overlap` of the smaller's cells are one space: nested, or
  /// sharing open_overlap with no room-bounding plane between their centres.
  bool sameOpenSpace(double overlap, const RoomObservation& a, const RoomObservation& b,
                     const std::map<uint32_t, WallLandmark>& bounding) const;
  /// Whether two corridor views on different axes close each other into one four-wall room:
  /// touching, each within the other's wall pair, no room-bounding plane between their centres
  /// (the strips of floor around a large table).
  bool closesAround(double overlap, const RoomObservation& a, const RoomObservation& b,
                    const std::map<uint32_t, WallLandmark>& landmarks,
                    const std::map<uint32_t, WallLandmark>& bounding) const;
  RoomAssociation mergeOrCreate(MappedRoom* match, const RoomObservation& observation,
                                bool union_free_space,
                                const std::map<uint32_t, WallLandmark>& landmarks);
  void mergeInto(MappedRoom* mapped, const RoomObservation& observation, bool union_free_space,
                 const std::map<uint32_t, WallLandmark>& landmarks, RoomAssociation* out);
  /// Merges mapped rooms nested in (or around) room out->room_id into the larger of each pair.
  void absorbNestedRooms(const std::map<uint32_t, WallLandmark>& landmarks,
                         const std::map<uint32_t, WallLandmark>& bounding, RoomAssociation* out);
  std::unordered_set<int64_t> cellsOf(const std::vector<Eigen::Vector3d>& pts) const;
  void remember(const std::map<uint32_t, WallLandmark>& landmarks);
  bool sameWall(int a, int b) const;

  RoomMergingConfig config_;
  std::map<uint32_t, MappedRoom> rooms_;
  std::map<uint32_t, WallMemo> wall_memo_;  // last known plane of every wall a room uses
  uint32_t next_id_ = 0;
};

}  // namespace tacs
