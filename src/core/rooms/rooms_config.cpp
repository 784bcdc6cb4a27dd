#include "tacs_graphs/rooms/rooms_config.h"

#include "tacs_graphs/common/config.h"

namespace tacs {

void TacsFreeSpaceConfig::validate() const {
  const std::string p = "rooms.tacs.";
  requireConfig(min_doorway_width >= 0.0, p + "min_doorway_width_m", "must be >= 0");
  requireConfig(max_doorway_width > min_doorway_width, p + "max_doorway_width_m",
                "must be > min_doorway_width");
  requireConfig(min_jamb_length >= 0.0, p + "min_jamb_length_m", "must be >= 0");
  requireConfig(jamb_max_angle_deg > 0.0 && jamb_max_angle_deg < 45.0, p + "jamb_max_angle_deg",
                "must be in (0, 45)");
  requireConfig(jamb_max_offset > 0.0, p + "jamb_max_offset_m", "must be > 0");
  requireConfig(max_keyframes_per_observation >= 1, p + "max_keyframes_per_observation",
                "must be >= 1");
  requireConfig(path_retry_radius >= 0.0, p + "path_retry_radius_m", "must be >= 0 (0 = off)");
  requireConfig(robot_search_radius > 0.0, p + "robot_search_radius_m", "must be > 0");
  requireConfig(local_radius >= 0.0, p + "local_radius_m", "must be >= 0");
  requireConfig(border_distance >= 0.0, p + "border_distance_m", "must be >= 0");
}

void VoxelFreeSpaceConfig::validate() const {
  const std::string p = "rooms.voxel.";
  requireConfig(resolution > 0.0, p + "resolution_m", "must be > 0");
  requireConfig(band_max > band_min, p + "band_max_m", "must be > band_min");
  requireConfig(max_ray_length > 0.0, p + "max_ray_length_m", "must be > 0");
  requireConfig(downsample >= 0.0, p + "downsample_m", "must be >= 0");
  requireConfig(min_hits >= 1, p + "min_hits", "must be >= 1");
  requireConfig(doorway_clearance >= 0.0, p + "doorway_clearance_m", "must be >= 0");
  requireConfig(min_cluster_area >= 0.0, p + "min_cluster_area_m2", "must be >= 0");
  requireConfig(update_every_keyframes >= 1, p + "update_every_keyframes", "must be >= 1");
  requireConfig(merge_distance > 0.0, p + "merge_distance_m", "must be > 0");
}

void RoomExtractionConfig::validate() const {
  const std::string p = "rooms.extraction.";
  requireConfig(adjacency_distance > 0.0, p + "adjacency_distance_m", "must be > 0");
  requireConfig(min_adjacent_length >= 0.0, p + "min_adjacent_length_m", "must be >= 0");
  requireConfig(max_behind_share >= 0.0, p + "max_behind_share", "must be >= 0");
  requireConfig(extent_margin >= 0.0, p + "extent_margin_m", "must be >= 0");
  requireConfig(min_width > 0.0, p + "min_width_m", "must be > 0");
  requireConfig(max_corridor_width > min_width, p + "max_corridor_width_m",
                "must be > min_width_m");
  requireConfig(min_free_space_points >= 1, p + "min_free_space_points", "must be >= 1");
  requireConfig(min_inside_share >= 0.0 && min_inside_share <= 1.0, p + "min_inside_share",
                "must be in [0, 1]");
  requireConfig(anchor_distance >= 0.0, p + "anchor_distance_m", "must be >= 0");
  requireConfig(wall_top_margin >= 0.0, p + "wall_top_margin_m", "must be >= 0");
  requireConfig(wall_top_min_share >= 0.0 && wall_top_min_share <= 1.0, p + "wall_top_min_share",
                "must be in [0, 1]");
}

void RoomMergingConfig::validate() const {
  const std::string p = "rooms.merging.";
  requireConfig(overlap_cell > 0.0, p + "overlap_cell_m", "must be > 0");
  requireConfig(min_overlap > 0.0 && min_overlap <= 1.0, p + "min_overlap", "must be in (0, 1]");
  requireConfig(max_axis_distance > 0.0, p + "max_axis_distance_m", "must be > 0");
  requireConfig(nested_overlap > 0.0 && nested_overlap <= 1.0, p + "nested_overlap",
                "must be in (0, 1]");
  requireConfig(open_overlap > 0.0 && open_overlap <= 1.0, p + "open_overlap", "must be in (0, 1]");
}

void RoomsConfig::validate() const {
  tacs.validate();
  voxel.validate();
  extraction.validate();
  merging.validate();
}

}  // namespace tacs
