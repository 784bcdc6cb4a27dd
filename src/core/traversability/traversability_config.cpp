#include "tacs_graphs/traversability/traversability_config.h"

#include <string>

#include "tacs_graphs/common/config.h"

namespace tacs {

namespace {
std::string field(const char* name) { return std::string("traversability.") + name; }
}  // namespace

void TraversabilityConfig::validate() const {
  requireConfig(resolution > 0.05 && resolution <= 5.0, field("resolution_m"),
                "must be in (0.05, 5] m");
  requireConfig(max_range >= 2 * resolution && max_range / resolution <= 2000, field("max_range_m"),
                "must be >= 2 * resolution and at most 2000 cells");
  requireConfig(min_range >= 0 && min_range < max_range, field("min_range_m"),
                "must be in [0, max_range)");
  requireConfig(obstacle_min_height > 0 && robot_height > obstacle_min_height,
                field("robot_height_m"), "need 0 < obstacle_min_height < robot_height");
  requireConfig(min_points >= 3, field("min_points"), "must be >= 3");
  requireConfig(seed_count >= 1, field("seed_count"), "must be >= 1");
  requireConfig(seed_margin > 0, field("seed_margin_m"), "must be > 0");
  requireConfig(plane_iterations >= 1, field("plane_iterations"), "must be >= 1");
  requireConfig(plane_distance > 0, field("plane_distance_m"), "must be > 0");
  requireConfig(max_slope_deg > 0 && max_slope_deg < 90, field("max_slope_deg"),
                "must be in (0, 90)");
  requireConfig(max_plane_thickness > 0, field("max_plane_thickness_m"), "must be > 0");
  requireConfig(min_plane_width >= 0, field("min_plane_width_m"), "must be >= 0");
  requireConfig(min_ground_height < max_ground_height, field("min_ground_height_m"),
                "must be < max_ground_height");
  requireConfig(max_step > 0, field("max_step_m"), "must be > 0");
  requireConfig(max_normal_change_deg > 0 && max_normal_change_deg < 90,
                field("max_normal_change_deg"), "must be in (0, 90)");
  requireConfig(bgk_length_scale > 0, field("bgk_length_scale_m"), "must be > 0");
  requireConfig(bgk_sigma0 > 0, field("bgk_sigma0"), "must be > 0");
  requireConfig(bgk_min_support >= 0, field("bgk_min_support"), "must be >= 0");
  requireConfig(bgk_min_ground_prob > 0 && bgk_min_ground_prob < 1, field("bgk_min_ground_prob"),
                "must be in (0, 1)");
  requireConfig(bgk_min_opposite >= 0 && bgk_min_opposite < 0.5, field("bgk_min_opposite"),
                "must be in [0, 0.5)");
  requireConfig(blind_radius_max >= 0, field("blind_radius_max_m"), "must be >= 0");
  requireConfig(root_search_radius >= 0, field("root_search_radius_m"), "must be >= 0");
  requireConfig(safe_clearance >= 0, field("safe_clearance_m"), "must be >= 0");
  requireConfig(clearance_subdivision >= 1 && clearance_subdivision <= 16,
                field("clearance_subdivision"), "must be in [1, 16]");
  // Below one obstacle-grid cell, a gap between two sampled wall points would let edges through.
  requireConfig(min_clearance >= resolution / clearance_subdivision, field("min_clearance_m"),
                "must be >= resolution / clearance_subdivision (one obstacle grid cell)");
  requireConfig(tilt_warning_deg > 0, field("tilt_warning_deg"), "must be > 0");
  requireConfig(map_resolution > 0, field("map_resolution_m"), "must be > 0");
  requireConfig(map_merge_height > 0, field("map_merge_height_m"), "must be > 0");
  map_retention.validate(field("map_retention."));
}

}  // namespace tacs
