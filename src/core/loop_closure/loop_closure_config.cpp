#include "tacs_graphs/loop_closure/loop_closure_config.h"

#include "tacs_graphs/common/config.h"

namespace tacs {

void LoopRegistrationConfig::validate() const {
  const std::string p = "loop_closure.registration.";
  requireConfig(keyframe_voxel_m >= 0.0, p + "keyframe_voxel_m", "must be >= 0 (0 = keep)");
  requireConfig(k_neighbors >= 3, p + "k_neighbors", "must be >= 3 (a plane needs 3 points)");
  requireConfig(max_iterations >= 1, p + "max_iterations", "must be >= 1");
  requireConfig(num_threads >= 0, p + "num_threads", "must be >= 0 (0 = OpenMP default)");
  requireConfig(score_search_radius_m > 0.0, p + "score_search_radius_m", "must be > 0");
  requireConfig(score_plane_distance_m > 0.0, p + "score_plane_distance_m", "must be > 0");
  requireConfig(score_max_normal_z > 0.0 && score_max_normal_z <= 1.0, p + "score_max_normal_z",
                "must be in (0, 1]");
  requireConfig(score_min_overlap > 0.0 && score_min_overlap <= 1.0, p + "score_min_overlap",
                "must be in (0, 1]");
  requireConfig(information_scale > 0.0, p + "information_scale", "must be > 0");
  requireConfig(tilt_information_scale > 0.0 && tilt_information_scale <= 1.0,
                p + "tilt_information_scale", "must be in (0, 1]");
  requireConfig(submap_length_m >= 0.0, p + "submap_length_m", "must be >= 0 (0 = single pair)");
  requireConfig(submap_voxel_m > 0.0, p + "submap_voxel_m", "must be > 0");
  requireConfig(robust_plane_distance_m >= 0.0, p + "robust_plane_distance_m",
                "must be >= 0 (0 = least squares)");
}

void CosgLoopConfig::validate() const {
  const std::string p = "loop_closure.cosg.";
  requireConfig(d_loop_m > 0.0, p + "d_loop_m", "must be > 0");
  requireConfig(partition_length_m > 0.0, p + "partition_length_m", "must be > 0");
  requireConfig(max_candidates_per_partition >= 1, p + "max_candidates_per_partition",
                "must be >= 1");
  requireConfig(min_id_separation >= 0, p + "min_id_separation", "must be >= 0");
  requireConfig(min_time_separation_s >= 0.0, p + "min_time_separation_s", "must be >= 0");
  requireConfig(coarse_correspondence_m > 0.0, p + "coarse_correspondence_m", "must be > 0");
  requireConfig(!fine_correspondence_schedule_m.empty(), p + "fine_correspondence_schedule_m",
                "must list at least one gate");
  for (double gate : fine_correspondence_schedule_m) {
    requireConfig(gate > 0.0, p + "fine_correspondence_schedule_m", "every gate must be > 0");
  }
  requireConfig(s_coarse > 0.0 && s_coarse <= 1.0, p + "s_coarse", "must be in (0, 1]");
  requireConfig(s_fine > 0.0 && s_fine <= s_coarse, p + "s_fine",
                "must be in (0, s_coarse] (the relaxed threshold)");
  requireConfig(max_fine_candidates >= 0, p + "max_fine_candidates", "must be >= 0 (0 = off)");
  requireConfig(min_loop_interval_m >= 0.0, p + "min_loop_interval_m", "must be >= 0 (0 = off)");
}

void DistanceLoopConfig::validate() const {
  const std::string p = "loop_closure.distance.";
  requireConfig(distance_threshold_m > 0.0, p + "distance_threshold_m", "must be > 0");
  requireConfig(accum_distance_m >= 0.0, p + "accum_distance_m", "must be >= 0");
  requireConfig(min_edge_interval_m >= 0.0, p + "min_edge_interval_m", "must be >= 0");
  requireConfig(max_correspondence_m > 0.0, p + "max_correspondence_m", "must be > 0");
  requireConfig(fitness_threshold > 0.0, p + "fitness_threshold_m2", "must be > 0");
}

void LoopClosureConfig::validate() const {
  registration.validate();
  cosg.validate();
  distance.validate();
  cloud_retention.validate("loop_closure.cloud_retention.");
}

}  // namespace tacs
