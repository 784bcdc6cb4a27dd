// The whole SLAM pipeline run synchronously in one thread of control, as tacs_offline and the
// evaluation use it (the same core classes the ROS nodes run, docs/DESIGN.md "Two ways to run the
// same core"). Per keyframe: traversability -> traversable map, walls -> backend landmarks, room
// segmentation -> backend rooms, loop detection (CoSG-LCD on a re-detected room, or the distance
// baseline) -> backend loops, then the scheduled optimisation. Deterministic for a given input.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "tacs_graphs/backend/backend.h"
#include "tacs_graphs/backend/map_export.h"
#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/loop_closure/loop_detector.h"
#include "tacs_graphs/odometry/external_odometry.h"
#include "tacs_graphs/odometry/lidar_odometry.h"
#include "tacs_graphs/pipeline/pipeline_config.h"
#include "tacs_graphs/rooms/room_segmenter.h"
#include "tacs_graphs/traversability/floor_frame.h"
#include "tacs_graphs/traversability/traversable_map.h"
#include "tacs_graphs/walls/wall_extractor.h"

namespace tacs {

/// What happened to one scan.
struct ScanOutcome {
  bool accepted = false;
  std::string error;  // why the scan was rejected (accepted == false)
  bool keyframe = false;
  uint32_t keyframe_id = 0;
  size_t walls = 0;        // wall observations of the keyframe
  size_t rooms = 0;        // room observations emitted at the keyframe
  size_t loops = 0;        // loop closures accepted at the keyframe
  bool optimized = false;  // the backend optimised after this scan
  bool recovered = false;  // the odometry re-aligned the scan from its yaw hypotheses
};

/// Counters of a run (timing.json).
struct PipelineStats {
  size_t scans = 0;
  size_t rejected_scans = 0;
  size_t deskewed_scans = 0;       // scans motion-compensated from their point times
  size_t odometry_recoveries = 0;  // registrations re-done from yaw hypotheses
  size_t keyframes = 0;
  size_t wall_observations = 0;
  size_t room_observations = 0;
  size_t room_redetections = 0;    // observations merged into a known room (CoSG-LCD triggers)
  size_t scans_outside_poses = 0;  // given poses: scans outside their time span (not used)
  std::string first_rejection;     // the reason of the first rejected scan, for the log
};

class Pipeline {
 public:
  /// Validates the configuration (throws ConfigError). T_base_sensor is the viewpoint of wall
  /// extraction and the ray origin of the voxel room baseline.
  explicit Pipeline(const PipelineConfig& config, const Pose3& T_base_sensor = Pose3::Identity());

  /// Processes one scan given in the base frame (the caller applies the sensor extrinsic). Never
  /// throws on bad data: the scan is rejected with a reason and the state is kept.
  /// `point_offsets_s`: optional per-point times relative to `stamp` (LidarOdometry::process).
  ScanOutcome processScan(double stamp, const PointCloud& scan_in_base,
                          const std::vector<float>* point_offsets_s = nullptr);

  /// Takes the odometry from given poses (T_odom_base by stamp, e.g. a trajectory file of another
  /// odometry or the reference) instead of GICP: each scan gets the pose interpolated at its
  /// stamp, and scans outside the poses' time span are skipped and counted. Call before the
  /// first scan. The keyframe information is that of a 2 cm / 0.5 deg motion.
  void useGivenPoses(const Trajectory& poses);

  /// Emits the room still being accumulated, then a final optimisation.
  void finish();

  const PipelineConfig& config() const { return config_; }
  const PipelineStats& stats() const { return stats_; }
  /// Odom-frame pose of every accepted scan.
  const Trajectory& odometryTrajectory() const { return odometry_; }
  /// Optimised keyframe poses in the map frame, by stamp.
  Trajectory keyframeTrajectory() const;
  SceneGraph sceneGraph() const { return backend_.sceneGraph(); }
  const Backend& backend() const { return backend_; }
  const KeyframeClouds& keyframeClouds() const { return map_clouds_.clouds(); }
  const StageTimes& stageTimes() const { return stage_times_; }
  /// Total backend optimisation time (t_FGO) and loop-detection time (t_LD) in seconds.
  double fgoSeconds() const { return backend_.totalOptimizationMs() / 1e3; }
  double ldSeconds() const { return loop_detector_.stats().total_ms / 1e3; }
  const LoopDetector& loopDetector() const { return loop_detector_; }
  const TraversableMap& traversableMap() const { return traversable_map_; }

 private:
  void processKeyframe(const OdometryResult& odom, ScanOutcome* outcome);
  /// Hands rooms to the backend; a room re-detection triggers CoSG-LCD (Sec. III-D).
  void applyRooms(const RoomSegmentationResult& result, uint32_t query_keyframe,
                  ScanOutcome* outcome);
  void applyLoops(const LoopDetection& detection, ScanOutcome* outcome);
  /// Optimised poses back into the traversable map and the loop detector.
  void propagatePoses(bool rebuild_traversable_map);
  /// The keyframe's ground frame in the map: the base itself, or the floor frame under it
  /// (traversability.find_floor_under_base).
  Pose3 groundPose(uint32_t id) const;
  /// Walls of the keyframe in its base frame, extracted from its ground-frame cloud.
  WallExtractionResult extractWalls(uint32_t id, const PointCloud& ground_cloud);

  PipelineConfig config_;
  LidarOdometry odometry_estimator_;
  std::unique_ptr<ExternalOdometry> given_poses_;  // set: odometry from given poses
  WallExtractor wall_extractor_;
  Eigen::Vector3d sensor_in_base_;  // wall extraction's viewpoint
  TraversabilityMapper traversability_mapper_;
  TraversableMap traversable_map_;
  RoomSegmenter room_segmenter_;
  LoopDetector loop_detector_;
  Backend backend_;
  std::vector<uint32_t> keyframe_ids_;       // in arrival (= stamp) order
  std::map<uint32_t, Pose3> base_to_floor_;  // find_floor_under_base: T_base_floor per keyframe
  FloorTracker floor_tracker_;               // ... and where the floor was last seen
  std::vector<double> keyframe_stamps_;
  bool loop_since_pose_update_ = false;
  PipelineStats stats_;
  Trajectory odometry_;
  MapClouds map_clouds_;
  StageTimes stage_times_;
};

}  // namespace tacs
