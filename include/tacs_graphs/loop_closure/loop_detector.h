// Loop-closure detection between keyframes.
//
// CoSG-LCD (paper Sec. III-D): run when a room observation is associated with a room already in
// the graph. Candidates are that room's keyframes within d_loop of the query, restricted to the
// two partitions of a large room nearest the query, searched nearest first. Each is registered
// with GICP from the current pose estimates; the best pair of each searched partition is a loop
// when it reaches S_coarse (Fig. 5(b)), unless its candidate lies within L_part along the path of
// an accepted loop's candidate (the same stretch of the earlier visit, which the odometry already
// holds together: the second loop would only repeat the first); a partition whose candidates all
// lie there is not registered at all. When no pair reaches S_coarse (large initial pose
// error), the weaker matches reaching the relaxed S_fine are refined coarse-to-fine, with
// correspondence gates shrinking from wide to narrow, and the refined best is a loop when it
// reaches S_coarse. The match score S is the share of the query's wall-like points, within the
// overlap with the candidate, that lie on the candidate's surfaces. A re-detection within
// cosg.min_loop_interval_m of travel after the last loop does not search: the path since was just
// corrected, a further loop would be redundant (Sec. III-D).
//
// An accepted pair's registration gives the loop's pose; with registration.submap_length_m > 0 it
// is registered once more between submaps (each keyframe's cloud merged with its neighbours' along
// the path). A loop's information is the GICP Hessian under the narrow gate at that pose (the
// unit-less plane covariances of gicp.h, as for the odometry's keyframe information) times
// registration.information_scale, its roll and pitch further damped by
// registration.tilt_information_scale.
//
// The distance baseline (hdl_graph_slam / S-Graphs+ style) runs on every keyframe: candidates
// within a fixed xy distance that lie far enough back along the path, the lowest GICP fitness
// wins when below a threshold.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/common/types.h"
#include "tacs_graphs/loop_closure/loop_closure_config.h"
#include "tacs_graphs/loop_closure/room_partitions.h"
#include "tacs_graphs/odometry/gicp.h"

namespace tacs {

/// Which acceptance path produced a loop.
enum class LoopPath { kCoarse, kFine, kDistance };
const char* loopPathName(LoopPath path);

/// One accepted loop closure, ready for Backend::addLoopClosure(from, to, T_from_to, information,
/// score). `from` is the older keyframe (the candidate), `to` the query.
struct LoopClosure {
  uint32_t from = 0;
  uint32_t to = 0;
  Pose3 T_from_to = Pose3::Identity();  // pose of keyframe `to` in the frame of keyframe `from`
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();  // x y z rx ry rz
  double score = 0.0;    // match score S in [0, 1] (higher is better)
  double fitness = 0.0;  // [m^2] GICP mean squared pair distance at the result
  LoopPath path = LoopPath::kCoarse;
};

/// What one detection call did.
struct LoopDetection {
  std::vector<LoopClosure> loops;      // accepted loops (CoSG: at most one per searched partition)
  std::vector<uint32_t> candidates;    // keyframes that passed the room / distance filters
  std::vector<uint32_t> registered;    // keyframes that were registered against the query
  std::vector<double> coarse_scores;   // CoSG: match score of each coarse registration, in order
  std::vector<uint32_t> refined;       // CoSG: weak matches refined coarse-to-fine
  std::vector<double> refined_scores;  // CoSG: their match scores after refinement
  std::vector<int> searched_partitions;  // CoSG: indices of the searched room partitions
  int partitions = 0;                    // CoSG: partitions of the room
  int registrations = 0;                 // GICP runs (a fine refinement counts each stage)
  std::string skipped;                   // non-empty: why nothing was tried
  double time_ms = 0.0;
};

/// Running totals over all detections (t_LD is total_ms).
struct LoopDetectorStats {
  int detections = 0;
  int registrations = 0;
  int coarse_loops = 0;
  int fine_loops = 0;
  int distance_loops = 0;
  double total_ms = 0.0;
};

class LoopDetector {
 public:
  /// Throws ConfigError when the configuration is invalid.
  explicit LoopDetector(const LoopClosureConfig& config);

  /// Stores a keyframe: its current map-frame pose estimate and its (downsampled) cloud in the
  /// base frame, prepared for GICP once. Re-adding an id replaces it. The clouds of old keyframes
  /// at places that hold enough clouds already are released (config cloud_retention); such
  /// keyframes still count in room extents but are no loop candidates.
  void addKeyframe(uint32_t id, double stamp, const Pose3& T_map_base, const PointCloud& cloud);
  /// New pose estimates (e.g. after an optimisation); unknown ids are ignored.
  void updatePoses(const std::map<uint32_t, Pose3>& T_map_base);
  bool hasKeyframe(uint32_t id) const { return keyframes_.count(id) > 0; }
  size_t keyframeCount() const { return keyframes_.size(); }
  /// Keyframes whose clouds are held (loop candidates).
  size_t cloudCount() const { return retention_.keptCount(); }
  /// Travelled distance along the added poses up to keyframe `id` [m] (0 when unknown).
  double accumulatedDistance(uint32_t id) const;

  /// CoSG-LCD: the room holding `room_keyframe_ids` was re-detected at keyframe `query_id`.
  LoopDetection detectInRoom(uint32_t query_id, const std::vector<uint32_t>& room_keyframe_ids);
  /// Distance baseline for keyframe `query_id` (call once per new keyframe).
  LoopDetection detectByDistance(uint32_t query_id);

  /// Match score S of the query placed at T_candidate_query in the candidate's frame.
  double matchScore(uint32_t candidate_id, uint32_t query_id, const Pose3& T_candidate_query) const;

  const LoopDetectorStats& stats() const { return stats_; }
  const LoopClosureConfig& config() const { return config_; }

 private:
  struct Keyframe {
    double stamp = 0.0;
    Pose3 T_map_base = Pose3::Identity();
    double accum_distance = 0.0;
    GicpCloud::ConstPtr cloud;
    std::vector<uint32_t> scored_points;  // wall-like points scored by matchScore()
  };
  struct Registration {
    uint32_t candidate = 0;
    GicpResult gicp;
    double score = 0.0;
  };

  /// GICP of the query against the candidate from `guess`; scored unless `score` is false.
  Registration registerPair(uint32_t candidate, uint32_t query, const Pose3& guess,
                            const GicpConfig& gicp, bool score = true) const;
  /// The registration settings under the correspondence gate `gate_m`, with the robust kernel
  /// (registration.robust_plane_distance_m) or plain least squares (wide gates, whose pairs
  /// must pull a pose from far).
  GicpConfig gicpConfig(double gate_m, bool robust) const;
  /// The loop of an accepted registration, with information; its pose refined between submaps
  /// when registration.submap_length_m > 0 (counted in `detection`).
  LoopClosure makeLoop(const Registration& r, uint32_t query, LoopPath path,
                       LoopDetection* detection) const;
  /// The cloud of keyframe `center` merged with those of its neighbours within
  /// submap_length_m / 2 of travel, in the frame of `center` by the current estimates. Only
  /// keyframes nearer along the path to `center` than to `other` (the pair's other keyframe) join,
  /// so the two submaps of a loop never share a scan. Null when no neighbour holds a cloud.
  GicpCloud::ConstPtr submap(uint32_t center, uint32_t other) const;
  bool isRecent(const Keyframe& candidate, uint32_t candidate_id, const Keyframe& query,
                uint32_t query_id) const;
  /// Less than `interval_m` of travel since the last accepted loop's query.
  bool soonAfterLastLoop(const Keyframe& query, double interval_m) const;
  /// Books a detection into the totals and remembers where its loops were closed.
  void finish(LoopDetection* detection, double elapsed_ms);
  LoopDetection skipped(const std::string& why, const Stopwatch& watch);
  /// CoSG-LCD coarse path over the searched partitions of the query's room; accepted loops go to
  /// `det`. Returns every registration made (the fine path's candidates).
  std::vector<Registration> coarsePath(uint32_t query_id, const std::vector<uint32_t>& room,
                                       const RoomPartitions& parts, LoopDetection* det);
  /// CoSG-LCD fine path: the best weak coarse matches re-registered coarse-to-fine.
  void finePath(uint32_t query_id, const std::vector<Registration>& coarse, LoopDetection* det);

  LoopClosureConfig config_;
  std::map<uint32_t, Keyframe> keyframes_;
  KeyframeRetention retention_;
  uint32_t last_added_ = 0;
  bool any_added_ = false;
  double last_loop_accum_ = -1.0;  // accum distance of the last accepted loop's query; < 0: none
  LoopDetectorStats stats_;
};

/// The query keyframe of CoSG-LCD for a re-detected room: the room's newest keyframe, the robot's
/// last one inside it (the keyframe that ended the observation may stand past the doorway, in the
/// next room, and overlap the room's keyframes only in part); `fallback` when the room has none.
uint32_t cosgQueryKeyframe(const std::vector<uint32_t>& room_keyframe_ids, uint32_t fallback);

}  // namespace tacs
