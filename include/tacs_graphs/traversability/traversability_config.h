// Configuration of the traversability module (pipeline config section `traversability`,
// documented key by key in config/default.yaml).
#pragma once

#include "tacs_graphs/common/keyframe_retention.h"

namespace tacs {

/// Parameters of the tri-grid terrain model (B-TMS style, paper Sec. II-C and III-A), the BGK
/// completion, the traversable/safe graph (Sec. III-B-2, eq. 1) and the map accumulation.
/// All heights are in the gravity-aligned base frame.
struct TraversabilityConfig {
  // --- tri-grid field
  double resolution = 0.4;  // square cell edge; each cell holds 4 triangular nodes [m]
  double max_range = 16.0;  // half width of the square grid around the robot [m]
  double min_range = 0.3;   // points closer than this (horizontally) are the robot itself [m]
  // --- robot
  double robot_floor_z = 0.0;  // height of the floor under the robot in the base frame [m]
  // The base is not on the floor (a hand-held sensor, a high mount with base = sensor): each
  // keyframe is levelled by its map roll and pitch and lowered onto the floor plane found below
  // it (traversability/floor_frame.h) before the terrain model sees it.
  bool find_floor_under_base = false;
  double robot_height = 1.2;         // top of the obstacle band above the local ground [m]
  double obstacle_min_height = 0.1;  // bottom of the obstacle band above the local ground [m]
  // --- per-node ground plane (iterative PCA from the lowest points)
  int min_points = 4;                 // fewer points: the node is UNKNOWN [-]
  int seed_count = 5;                 // lowest points averaged into the seed height [-]
  double seed_margin = 0.15;          // seeds: points up to this above the seed height [m]
  int plane_iterations = 3;           // PCA refits [-]
  double plane_distance = 0.06;       // |point-plane distance| of ground points [m]
  double max_slope_deg = 20.0;        // steeper planes are NONGROUND [deg]
  double max_plane_thickness = 0.05;  // sqrt of the smallest eigenvalue; thicker: NONGROUND [m]
  double min_plane_width = 0.04;      // sqrt of the middle eigenvalue; thinner: a line [m]
  double max_ground_height = 0.5;     // ground planes higher above the robot's floor: NONGROUND [m]
  double min_ground_height = -3.0;    // ground planes lower below the robot's floor: NONGROUND [m]
  // --- local convexity/concavity edge test between neighbouring nodes
  double max_step = 0.1;                // largest height offset across an edge [m]
  double max_normal_change_deg = 15.0;  // largest angle between neighbouring normals [deg]
  // --- BGK completion of unobserved nodes (sparse kernel of Melkumyan and Ramos)
  double bgk_length_scale = 0.6;     // kernel support [m]
  double bgk_sigma0 = 1.0;           // kernel scale [-]
  double bgk_min_support = 0.5;      // minimal kernel mass of ground evidence [-]
  double bgk_min_ground_prob = 0.6;  // posterior ground probability to infer GROUND [-]
  double bgk_min_opposite = 0.15;    // share of the evidence opposite its dominant direction [-]
  double blind_radius_max = 3.0;     // largest sensor blind disc filled from the ground around [m]
  // --- graph
  double root_search_radius = 0.6;  // look this far from the robot for the root node [m]
  double min_clearance = 0.15;      // traversable centroids and moves keep this off obstacles [m]
  double safe_clearance = 0.4;      // lambda_o of eq. 1: safe triangles are at least this far [m]
  int clearance_subdivision = 4;    // obstacle distance grid cells per tri-grid cell edge [-]
  double tilt_warning_deg = 5.0;    // warn when the ground near the robot tilts more [deg]
  // --- map accumulation (TraversableMap)
  double map_resolution = 0.2;            // cell of the map-frame node hash [m]
  double map_merge_height = 0.3;          // nodes of one hash cell closer in z are merged [m]
  KeyframeRetentionConfig map_retention;  // keyframe graphs kept per place over long runs

  template <class V>
  void visit(V& v) {
    v("resolution_m", resolution);
    v("max_range_m", max_range);
    v("min_range_m", min_range);
    v("robot_floor_z_m", robot_floor_z);
    v("find_floor_under_base", find_floor_under_base);
    v("robot_height_m", robot_height);
    v("obstacle_min_height_m", obstacle_min_height);
    v("min_points", min_points);
    v("seed_count", seed_count);
    v("seed_margin_m", seed_margin);
    v("plane_iterations", plane_iterations);
    v("plane_distance_m", plane_distance);
    v("max_slope_deg", max_slope_deg);
    v("max_plane_thickness_m", max_plane_thickness);
    v("min_plane_width_m", min_plane_width);
    v("max_ground_height_m", max_ground_height);
    v("min_ground_height_m", min_ground_height);
    v("max_step_m", max_step);
    v("max_normal_change_deg", max_normal_change_deg);
    v("bgk_length_scale_m", bgk_length_scale);
    v("bgk_sigma0", bgk_sigma0);
    v("bgk_min_support", bgk_min_support);
    v("bgk_min_ground_prob", bgk_min_ground_prob);
    v("bgk_min_opposite", bgk_min_opposite);
    v("blind_radius_max_m", blind_radius_max);
    v("root_search_radius_m", root_search_radius);
    v("min_clearance_m", min_clearance);
    v("safe_clearance_m", safe_clearance);
    v("clearance_subdivision", clearance_subdivision);
    v("tilt_warning_deg", tilt_warning_deg);
    v("map_resolution_m", map_resolution);
    v("map_merge_height_m", map_merge_height);
    v("map_retention", map_retention);
  }
  /// Throws ConfigError naming the field ("traversability.<field>: ...").
  void validate() const;
};

}  // namespace tacs
