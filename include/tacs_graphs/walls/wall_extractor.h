// Wall extraction by sequential RANSAC (paper Sec. III-B-1, "Wall Layer Segmentation").
//
// Per keyframe cloud in the gravity-aligned base frame: voxel downsampling, then planes are found
// one after the other, largest first, and their inliers removed. Hypotheses are drawn from three
// points of one neighbourhood (so walls that hold a few percent of the cloud are still sampled),
// scored on a random subsample, and the best one is refined by PCA on its inliers. Vertical
// planes become wall observations after splitting their inliers into runs along the wall, so one
// plane model never joins two collinear walls with a gap between them (a door, a second room).
// Horizontal planes (floor, ceiling, table tops) are reported apart; slanted planes are dropped.
// Deterministic for a given cloud and seed.
#pragma once

#include <cstdint>
#include <vector>

#include "tacs_graphs/common/types.h"
#include "tacs_graphs/walls/wall_segment.h"

namespace tacs {

struct WallExtractionConfig {
  /// Voxel size of the downsampling before RANSAC (m); 0 keeps every point.
  double voxel_size = 0.1;
  /// Points closer to / farther from the base origin than this are ignored (m).
  double min_range = 0.5;
  double max_range = 30.0;
  /// Point-to-plane distance below which a point supports a plane (m).
  double distance_threshold = 0.05;
  /// Hypotheses drawn per extracted plane.
  int ransac_iterations = 200;
  /// Points a hypothesis is scored on (random subsample of the points still unexplained).
  int score_subsample = 1024;
  /// Edge of the neighbourhood cells the three sample points are drawn from (m).
  double sample_cell = 1.5;
  /// Least-squares (PCA) refinements of the best hypothesis on its inliers.
  int refine_iterations = 3;
  /// Upper bound on planes extracted per cloud.
  int max_planes = 30;
  /// Stop when fewer unexplained points than this remain.
  int min_remaining_points = 100;
  /// Stop when the best remaining plane has fewer inliers than this.
  int min_plane_inliers = 40;
  /// A plane is vertical when its normal is within this angle of the horizontal plane (deg).
  double vertical_tolerance_deg = 5.0;
  /// A plane is horizontal when its normal is within this angle of the z axis (deg).
  double horizontal_tolerance_deg = 10.0;
  /// Inliers of a vertical plane further apart than this along the wall start a new segment (m).
  double max_gap = 0.5;
  /// Inliers within this height of the plane's lowest or highest inlier (where the floor and the
  /// ceiling cross the wall's plane) neither bridge a gap nor extend a segment: through a doorway
  /// they would join the walls on both sides (m); 0 treats them like the others.
  double edge_band = 0.15;
  /// A wall segment needs at least this many inliers...
  int min_wall_inliers = 60;
  /// ...this length (m)...
  double min_wall_length = 0.6;
  /// ...this height range (m)...
  double min_wall_height = 0.3;
  /// ...and inliers along at least this share of its length (bins of max(0.1, 2 voxel_size) m).
  double min_coverage = 0.6;
  /// A wall reaches this high above the sensor (m). A segment whose top stays lower while the
  /// sensor's upper beams pass above it at that range is a low surface (furniture side, half wall,
  /// parapet), not a wall; a top cut by the field of view (near walls) is no evidence. 0 = off.
  double min_wall_top = 1.0;
  // A wall starts this low above the sensor at most (m; 0 = off): higher, it hangs from the
  // ceiling (a beam, a duct, a clerestory). For a sensor carried above the furniture.
  double max_wall_bottom = 0.0;
  /// A top within this elevation of the scan's highest beam is cut by the field of view (deg).
  double fov_top_margin_deg = 3.0;
  /// A stretch of max_gap along a segment over whose top the scan saw this many points of a
  /// surface beyond it (rays that cross the segment's line there above its top) stands in front
  /// of something: a cabinet, a shelf, a half wall, not a wall, which meets the ceiling. Such
  /// stretches are cut out of the segment. 0 = off.
  int seen_over_min_points = 3;
  /// ...points at least this far behind the segment's plane (m)...
  double seen_over_depth = 0.15;
  /// ...on rays at least this far above the stretch's top where they cross it (m).
  double seen_over_clearance = 0.1;
  /// A segment in front of same-facing walls of the same scan, more than distance_threshold and
  /// at most this far in front of their planes, that spans it or flanks both its ends, is a door,
  /// cabinet or panel on that wall and not reported (m); 0 = off.
  double on_wall_max_depth = 0.6;
  /// Horizontal planes with fewer inliers are not reported (their points are still removed).
  int min_horizontal_inliers = 200;
  /// Seed of the random sampling.
  int seed = 1;

  template <class V>
  void visit(V& v) {
    v("voxel_size_m", voxel_size);
    v("min_range_m", min_range);
    v("max_range_m", max_range);
    v("distance_threshold_m", distance_threshold);
    v("ransac_iterations", ransac_iterations);
    v("score_subsample", score_subsample);
    v("sample_cell_m", sample_cell);
    v("refine_iterations", refine_iterations);
    v("max_planes", max_planes);
    v("min_remaining_points", min_remaining_points);
    v("min_plane_inliers", min_plane_inliers);
    v("vertical_tolerance_deg", vertical_tolerance_deg);
    v("horizontal_tolerance_deg", horizontal_tolerance_deg);
    v("max_gap_m", max_gap);
    v("edge_band_m", edge_band);
    v("min_wall_inliers", min_wall_inliers);
    v("min_wall_length_m", min_wall_length);
    v("min_wall_height_m", min_wall_height);
    v("min_coverage", min_coverage);
    v("min_wall_top_m", min_wall_top);
    v("max_wall_bottom_m", max_wall_bottom);
    v("fov_top_margin_deg", fov_top_margin_deg);
    v("seen_over_min_points", seen_over_min_points);
    v("seen_over_depth_m", seen_over_depth);
    v("seen_over_clearance_m", seen_over_clearance);
    v("on_wall_max_depth_m", on_wall_max_depth);
    v("min_horizontal_inliers", min_horizontal_inliers);
    v("seed", seed);
  }
  /// Throws ConfigError naming the field ("walls.extraction.<field>").
  void validate() const;
};

struct WallExtractionResult {
  /// Vertical wall segments in the cloud's frame, d >= 0, sorted by decreasing inliers.
  std::vector<WallSegment> walls;
  /// Vertical surfaces the sensor saw over, so not walls (cabinets, shelves, half walls): runs too
  /// low for a wall and the stretches cut out of segments as seen over; by decreasing inliers.
  /// Seen from too close to see over them, the same surfaces come out as walls: a map that
  /// remembers these can tell (WallMap::addSeenOver).
  std::vector<WallSegment> seen_over;
  /// Horizontal planes (floor, ceiling, ...), endpoints = xy bounding box, by decreasing inliers.
  std::vector<WallSegment> horizontal;
  /// Points given, points after range cropping and downsampling.
  size_t input_points = 0;
  size_t downsampled_points = 0;
  /// Planes extracted by RANSAC (vertical, horizontal and slanted).
  int planes_found = 0;
  double time_ms = 0.0;
};

/// extract() is const and safe to call from several threads: its working buffers (a voxel key
/// indexer, the downsampled points, the sampling cells) are per thread (thread_local in the .cpp)
/// and kept between calls, since fresh multi-megabyte allocations cost more than the work on them.
class WallExtractor {
 public:
  /// Validates the configuration (throws ConfigError).
  explicit WallExtractor(const WallExtractionConfig& config);

  /// Extracts walls from a cloud in the gravity-aligned base frame (z up). Normals are turned to
  /// face `viewpoint` (the sensor position in that frame; for walls only its xy matters), which
  /// gives d >= 0 whenever the viewpoint is at the origin.
  WallExtractionResult extract(const PointCloud& cloud_in_base,
                               const Eigen::Vector3d& viewpoint = Eigen::Vector3d::Zero()) const;

  /// Extracts from a cloud in a base frame that is not gravity-aligned (a hand-held sensor): in
  /// the levelled frame `T_base_level` (e.g. FloorFrame::T_base_floor), where walls are vertical,
  /// and returns the segments in the base frame. `viewpoint_in_base`: the sensor in the base.
  WallExtractionResult extractInFrame(const PointCloud& cloud_in_level, const Pose3& T_base_level,
                                      const Eigen::Vector3d& viewpoint_in_base) const;

  const WallExtractionConfig& config() const { return config_; }

 private:
  WallExtractionConfig config_;
};

}  // namespace tacs
