// Configuration of room segmentation (pipeline config section `rooms`, documented key by key in
// config/default.yaml): the free-space segmentation (TACS, paper Sec. III-B-2, or the voxel
// baseline in the style of S-Graphs+), the room extraction from walls (Sec. III-B-3) and the room
// merging module (Sec. III-C).
#pragma once

#include <string>

#include "tacs_graphs/common/config.h"

namespace tacs {

/// rooms.method: traversable free space (the paper), the S-Graphs+ style voxel baseline, or no
/// rooms (odometry and walls only).
enum class RoomMethod { kTacs, kVoxel, kNone };
template <>
struct EnumNames<RoomMethod> {
  static constexpr std::array<std::pair<RoomMethod, const char*>, 3> kNames{
      {{RoomMethod::kTacs, "tacs"}, {RoomMethod::kVoxel, "voxel"}, {RoomMethod::kNone, "none"}}};
};

/// rooms.voxel.merging: how a new voxel room joins the map.
enum class VoxelMerging { kCenterDistance, kModule };
template <>
struct EnumNames<VoxelMerging> {
  static constexpr std::array<std::pair<VoxelMerging, const char*>, 2> kNames{
      {{VoxelMerging::kCenterDistance, "center_distance"}, {VoxelMerging::kModule, "module"}}};
};

/// Traversability-aware free-space segmentation (paper eq. 1-3).
struct TacsFreeSpaceConfig {
  /// Openings between two collinear wall landmarks of the same facing (a door, a gap in a half
  /// wall) up to this width are doorways: safe-graph edges through them are cut, so rooms split
  /// there even when the opening is wider than 2 * safe_clearance [m].
  double max_doorway_width = 3.2;
  /// Narrower openings are gaps in the observation of one wall, not doorways [m].
  double min_doorway_width = 0.5;
  /// Both wall pieces beside a doorway must be at least this long (pillars and cabinet faces
  /// are not door jambs) [m].
  double min_jamb_length = 1.0;
  /// Walls beside a doorway: largest angle between their normals [deg] and largest distance
  /// between their planes at the gap [m].
  double jamb_max_angle_deg = 8.0;
  double jamb_max_offset = 0.25;
  /// A room observation is also emitted after this many keyframes in one region, so a robot that
  /// stays in one room still reports it (the next observation is merged into it) [-].
  int max_keyframes_per_observation = 40;
  /// A region no pair of facing walls bounds (one around a corner of two corridors) is extracted
  /// again from its free space within this distance (xy) of the robot's positions in it; 0 = off
  /// [m].
  double path_retry_radius = 4.0;
  /// The robot is on the safe node nearest to it within this radius (xy) [m].
  double robot_search_radius = 0.4;
  /// T_inside of a keyframe is its room-graph component within this distance (xy) of the robot,
  /// the reach of one keyframe's local traversable graph; 0 takes the whole component [m].
  double local_radius = 16.0;
  /// Traversable but unsafe nodes within this distance of a room's safe nodes join the room
  /// (its free space then reaches the walls); 0 keeps the safe nodes only [m].
  double border_distance = 0.6;

  template <class V>
  void visit(V& v) {
    v("max_doorway_width_m", max_doorway_width);
    v("min_doorway_width_m", min_doorway_width);
    v("min_jamb_length_m", min_jamb_length);
    v("jamb_max_angle_deg", jamb_max_angle_deg);
    v("jamb_max_offset_m", jamb_max_offset);
    v("max_keyframes_per_observation", max_keyframes_per_observation);
    v("path_retry_radius_m", path_retry_radius);
    v("robot_search_radius_m", robot_search_radius);
    v("local_radius_m", local_radius);
    v("border_distance_m", border_distance);
  }
  void validate() const;
};

/// Voxel free-space baseline in the style of S-Graphs+ (reference/s_graphs.md, Sec. 2): an
/// occupancy slice at robot height from the keyframe clouds, cells within `doorway_clearance` of
/// an obstacle removed, connected components as room candidates.
struct VoxelFreeSpaceConfig {
  double resolution = 0.1;         // 2D cell of the occupancy slice [m]
  double band_min = 0.3;           // slice band above the robot's floor, bottom [m]
  double band_max = 1.8;           // slice band above the robot's floor, top [m]
  double max_ray_length = 15.0;    // rays are integrated up to this range [m]
  double downsample = 0.15;        // voxel size applied to keyframe clouds before ray casting [m]
  int min_hits = 2;                // a cell with this many returns is occupied [-]
  double doorway_clearance = 0.8;  // free cells this close to an obstacle are cut [m]
  double min_cluster_area = 1.5;   // smaller clusters are dropped [m^2]
  int update_every_keyframes = 4;  // clusters are recomputed every this many keyframes [-]
  double merge_distance = 1.0;     // rooms closer than this (centre, 2D) are one room [m]
  /// How a new room joins the map: "center_distance" (S-Graphs+, `merge_distance`) or "module"
  /// (the room merging module of Sec. III-C, `rooms.merging`: the paper's baseline + RM).
  VoxelMerging merging = VoxelMerging::kCenterDistance;

  template <class V>
  void visit(V& v) {
    v("resolution_m", resolution);
    v("band_min_m", band_min);
    v("band_max_m", band_max);
    v("max_ray_length_m", max_ray_length);
    v("downsample_m", downsample);
    v("min_hits", min_hits);
    v("doorway_clearance_m", doorway_clearance);
    v("min_cluster_area_m2", min_cluster_area);
    v("update_every_keyframes", update_every_keyframes);
    v("merge_distance_m", merge_distance);
    v("merging", merging);
  }
  void validate() const;
};

/// Room extraction from a free-space region and the wall landmarks (paper Sec. III-B-3).
struct RoomExtractionConfig {
  /// Free-space points within this distance in front of a wall (and along its extent) are
  /// adjacent to it [m].
  double adjacency_distance = 1.5;
  /// A wall bounds the region when its adjacent free-space points cover at least this length
  /// along it (0.2 m bins), so a region touching a wall's end only is not bounded by it [m].
  double min_adjacent_length = 1.0;
  /// A face with free space right behind it along more than this share of its adjacent length
  /// stands inside the region (furniture, a pillar), it does not bound it [-].
  double max_behind_share = 0.5;
  /// Walls are searched this far past their extent along the wall [m].
  double extent_margin = 0.5;
  /// Facing walls must be at least this far apart [m].
  double min_width = 1.0;
  /// Method "tacs": one facing pair farther apart than this around a region that free-standing
  /// furniture closes on the other axis is no corridor but part of a hall (between a
  /// supermarket's long walls, beside its gondola rows): it joins the mapped room sharing one of
  /// those walls (RoomMap::addUnbounded); with none mapped yet it stays a room of its own [m].
  double max_corridor_width = 5.0;
  /// Free-space regions with fewer points are not rooms [-].
  int min_free_space_points = 30;
  /// Share of the free-space points that must lie between a pair of facing walls [-].
  double min_inside_share = 0.6;
  /// Free space more than this behind one of a room's own walls (within the wall's extent) is no
  /// part of the room: a region that leaked through a door in the wall keeps only its part
  /// inside. Space beside a wall's end stays (an L-shaped room). Negative: keep it all [m].
  double outside_margin = 0.3;
  /// Method "tacs": a plane that is no wall bounds a room only when an end of it lies within this
  /// distance of a wall or of a plane anchored so; free-standing furniture bounds none (open-plan
  /// halls, rooms/room_bounds.h). 0: every plane may bound a room, as the voxel baseline keeps
  /// [m].
  double anchor_distance = 0.5;
  /// Method "tacs": a wall-shaped plane whose top is more than this below the tallest wall's has
  /// furniture height and, like furniture, bounds a room only when anchored [m].
  double wall_top_margin = 1.5;
  /// Method "tacs": ... or whose top is below this share of the tallest wall's (the floor's
  /// ceiling height) [-].
  double wall_top_min_share = 0.75;

  template <class V>
  void visit(V& v) {
    v("adjacency_distance_m", adjacency_distance);
    v("min_adjacent_length_m", min_adjacent_length);
    v("max_behind_share", max_behind_share);
    v("extent_margin_m", extent_margin);
    v("min_width_m", min_width);
    v("max_corridor_width_m", max_corridor_width);
    v("min_free_space_points", min_free_space_points);
    v("min_inside_share", min_inside_share);
    v("outside_margin_m", outside_margin);
    v("anchor_distance_m", anchor_distance);
    v("wall_top_margin_m", wall_top_margin);
    v("wall_top_min_share", wall_top_min_share);
  }
  void validate() const;
};

/// Room merging (paper Sec. III-C).
struct RoomMergingConfig {
  /// Free-space cells used to measure the overlap of two rooms [m].
  double overlap_cell = 0.4;
  /// Two rooms overlap when this share of the smaller one's free-space cells is shared [-].
  double min_overlap = 0.3;
  /// Largest centre distance along the axes orthogonal to the rooms' walls [m] (d(x) of eq. 4).
  double max_axis_distance = 1.0;
  /// A room whose cells lie in another by at least this share is merged into it whatever its
  /// centre (a first, partial view of a room whose walls were not all seen yet) [-].
  double nested_overlap = 0.8;
  /// Rooms sharing this share of the smaller one's cells, with no room-bounding plane between
  /// their centres, are one room (views of an L-shaped open-plan floor from its two legs) [-].
  double open_overlap = 0.5;

  template <class V>
  void visit(V& v) {
    v("overlap_cell_m", overlap_cell);
    v("min_overlap", min_overlap);
    v("max_axis_distance_m", max_axis_distance);
    v("nested_overlap", nested_overlap);
    v("open_overlap", open_overlap);
  }
  void validate() const;
};

struct RoomsConfig {
  RoomMethod method = RoomMethod::kTacs;
  TacsFreeSpaceConfig tacs;
  VoxelFreeSpaceConfig voxel;
  RoomExtractionConfig extraction;
  RoomMergingConfig merging;

  template <class V>
  void visit(V& v) {
    v("method", method);
    v("tacs", tacs);
    v("voxel", voxel);
    v("extraction", extraction);
    v("merging", merging);
  }
  /// Throws ConfigError naming the field ("rooms.<field>: ...").
  void validate() const;
};

}  // namespace tacs
