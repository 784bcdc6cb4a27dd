// Section `loop_closure` of the pipeline configuration: room-triggered CoSG-LCD (paper Sec. III-D)
// and the distance-threshold baseline in the style of hdl_graph_slam / S-Graphs+ (Sec. IV-A).
#pragma once

#include <string>
#include <vector>

#include "tacs_graphs/common/config.h"
#include "tacs_graphs/common/keyframe_retention.h"

namespace tacs {

/// loop_closure.method: room-triggered CoSG-LCD (the paper), the distance-threshold baseline on
/// every keyframe, or none.
enum class LoopMethod { kCosg, kDistance, kNone };
template <>
struct EnumNames<LoopMethod> {
  static constexpr std::array<std::pair<LoopMethod, const char*>, 3> kNames{
      {{LoopMethod::kCosg, "cosg"},
       {LoopMethod::kDistance, "distance"},
       {LoopMethod::kNone, "none"}}};
};

/// Keyframe preparation and the GICP settings shared by both detectors.
struct LoopRegistrationConfig {
  double keyframe_voxel_m = 0.0;  // [m] extra voxel downsampling of keyframe clouds; 0 keeps them
  int k_neighbors = 10;           // points per GICP covariance
  int max_iterations = 30;        // GICP iterations per registration stage
  int num_threads = 2;            // OpenMP threads of GICP; 0 = OpenMP default
  // Match score (CoSG-LCD's S): share of the query's wall-like points in the overlap with the
  // candidate that lie on a surface of the candidate. Horizontal surfaces (floor, ceiling) are
  // left out because they agree under any planar shift or yaw, so they would inflate the score
  // of a wrong alignment.
  double score_search_radius_m = 1.0;    // [m] query points farther from the candidate: no overlap
  double score_plane_distance_m = 0.08;  // [m] a match lies this close to the candidate's plane
  double score_max_normal_z = 0.5;       // |normal z| above this: horizontal, not scored [-]
  double score_min_overlap = 0.3;        // the overlap counts as at least this share [-]
  // Scale of the GICP Hessian given as loop information. The Hessian counts every point pair as
  // an independent measurement. An odometry edge carries the same kind of pair Hessian, but its
  // pose comes from scan-to-map registration; a loop's pose comes from two single scans and is
  // off by 1-7 mm against the ground truth on the simulated worlds.
  double information_scale = 0.1;
  // Further scale of the loop information's roll and pitch (rows and columns rx, ry scaled by its
  // square root). Two single scans of a floor seen as sparse rings register with tilt errors of
  // 0.05-0.35 deg (yaw 0.01 deg); held at that weight they bend the map's height, which odometry
  // and the vertical walls already level. 1 keeps the Hessian's tilt.
  double tilt_information_scale = 0.01;
  // With submap_length_m > 0 an accepted loop's pose is registered once more between submaps: each
  // keyframe's cloud merged with those of its neighbours within submap_length_m / 2 along the
  // path, placed by the current estimates. Several viewpoints fill the gaps between one scan's
  // sparse rings, and a submap loop cannot settle on a pose 0.1 m off as a single pair of the
  // distance baseline sometimes does. CoSG-LCD's pairs, chosen by match score, gain nothing from
  // it (wATE 0.0033 m either way, results/README.md) while it costs 8-60 ms per loop, so the
  // default is the single pair, as in the paper and hdl_graph_slam (0).
  double submap_length_m = 0.0;  // [m] path around each keyframe of the pair merged into its submap
  double submap_voxel_m = 0.2;   // [m] voxel of the merged submaps
  // [m] Geman-McClure kernel (GicpConfig::robust_plane_distance_m) of the narrow-gate
  // registrations: the coarse path and the submaps. Two views, and even more two submaps of
  // different stretches of the path, each hold surfaces the other lacks; those pair with surfaces
  // nearby and, under least squares, tilted and shifted loops by up to 0.4 deg and 2 cm. 0: least
  // squares.
  double robust_plane_distance_m = 0.03;

  template <class V>
  void visit(V& v) {
    v("keyframe_voxel_m", keyframe_voxel_m);
    v("k_neighbors", k_neighbors);
    v("max_iterations", max_iterations);
    v("num_threads", num_threads);
    v("score_search_radius_m", score_search_radius_m);
    v("score_plane_distance_m", score_plane_distance_m);
    v("score_max_normal_z", score_max_normal_z);
    v("score_min_overlap", score_min_overlap);
    v("information_scale", information_scale);
    v("tilt_information_scale", tilt_information_scale);
    v("submap_length_m", submap_length_m);
    v("submap_voxel_m", submap_voxel_m);
    v("robust_plane_distance_m", robust_plane_distance_m);
  }
  void validate() const;
};

/// CoSG-LCD (paper Sec. III-D, Fig. 5): candidates from the re-detected room only.
struct CosgLoopConfig {
  double d_loop_m = 5.0;            // [m] d_th^loop: candidates this close to the query (estimates)
  double partition_length_m = 8.0;  // [m] L_part along the room's long axis
  int max_candidates_per_partition = 3;   // nearest candidates registered per searched partition
  int min_id_separation = 20;             // [keyframes] younger candidates are the same visit
  double min_time_separation_s = 20.0;    // [s] ... and so are candidates this recent
  double coarse_correspondence_m = 0.25;  // [m] GICP pair gating of the coarse (direct) path
  // [m] GICP pair gating per stage of the fine path, wide to narrow: a wide gate pulls a pose
  // that is off by up to ~1 m and ~10 deg into the basin of the narrow one.
  std::vector<double> fine_correspondence_schedule_m = {2.5, 1.2, 0.5};
  double s_coarse = 0.85;       // S_coarse: a registration with this score is a loop [-]
  double s_fine = 0.4;          // S_fine: weaker matches with at least this score are refined [-]
  int max_fine_candidates = 3;  // best weak matches refined coarse-to-fine per detection
  // [m] travel since the last accepted loop before a re-detection searches again: a room entered
  // right after a loop lies on a path that loop has just corrected (same rule as the baseline's
  // min_edge_interval_m). 0 searches on every re-detection.
  double min_loop_interval_m = 5.0;

  template <class V>
  void visit(V& v) {
    v("d_loop_m", d_loop_m);
    v("partition_length_m", partition_length_m);
    v("max_candidates_per_partition", max_candidates_per_partition);
    v("min_id_separation", min_id_separation);
    v("min_time_separation_s", min_time_separation_s);
    v("coarse_correspondence_m", coarse_correspondence_m);
    v("fine_correspondence_schedule_m", fine_correspondence_schedule_m);
    v("s_coarse", s_coarse);
    v("s_fine", s_fine);
    v("max_fine_candidates", max_fine_candidates);
    v("min_loop_interval_m", min_loop_interval_m);
  }
  void validate() const;
};

/// Distance-threshold baseline (hdl_graph_slam style), run on every keyframe.
struct DistanceLoopConfig {
  double distance_threshold_m = 3.0;  // [m] candidates this close in xy (estimates)
  double accum_distance_m = 8.0;      // [m] ... and at least this far back along the path
  double min_edge_interval_m = 5.0;   // [m] travel since the last accepted loop before the next
  double max_correspondence_m = 2.5;  // [m] GICP pair gating
  double fitness_threshold = 0.5;     // [m^2] accept the best candidate below this mean sq. error

  template <class V>
  void visit(V& v) {
    v("distance_threshold_m", distance_threshold_m);
    v("accum_distance_m", accum_distance_m);
    v("min_edge_interval_m", min_edge_interval_m);
    v("max_correspondence_m", max_correspondence_m);
    v("fitness_threshold_m2", fitness_threshold);
  }
  void validate() const;
};

struct LoopClosureConfig {
  LoopMethod method = LoopMethod::kCosg;
  LoopRegistrationConfig registration;
  CosgLoopConfig cosg;
  DistanceLoopConfig distance;
  KeyframeRetentionConfig cloud_retention;  // candidate clouds kept per place over long runs

  template <class V>
  void visit(V& v) {
    v("method", method);
    v("registration", registration);
    v("cosg", cosg);
    v("distance", distance);
    v("cloud_retention", cloud_retention);
  }
  void validate() const;
};

}  // namespace tacs
