// The whole SLAM pipeline run synchronously in one thread of control, as tacs_offline and the
// evaluation use it: the stage sessions the ROS nodes run one per process (keyframe_stages.h,
// BackendSession, RoomSegmentationSession, LoopClosureSession), composed here in one process
// (docs/DESIGN.md "One wiring"). Per keyframe: backend keyframe, walls -> backend landmarks,
// traversability -> room segmentation -> backend rooms, loop detection (CoSG-LCD on a re-detected
// room, or the distance baseline) -> backend loops, then the scheduled optimisation.
// Deterministic for a given input.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/odometry/external_odometry.h"
#include "tacs_graphs/odometry/lidar_odometry.h"
#include "tacs_graphs/pipeline/backend_session.h"
#include "tacs_graphs/pipeline/keyframe_stages.h"
#include "tacs_graphs/pipeline/loop_closure_session.h"
#include "tacs_graphs/pipeline/pipeline_config.h"
#include "tacs_graphs/pipeline/room_segmentation_session.h"

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

/// The odometry half of Pipeline::processScan for one scan.
struct ScanOdometry {
  bool outside_given_poses = false;  // given poses: the stamp lies outside their time span
  OdometryResult odometry;
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

  /// processScan in two halves, so that the odometry of later scans can run on one thread while
  /// the keyframe stages of earlier ones run on another (tacs_offline): odometryOf reads and
  /// changes only the odometry's state, takeOdometry everything else. Calling both in scan order
  /// gives what processScan gives, whichever thread runs which half.
  ScanOdometry odometryOf(double stamp, const PointCloud& scan_in_base,
                          const std::vector<float>* point_offsets_s = nullptr);
  ScanOutcome takeOdometry(const ScanOdometry& scan);
  /// odometryOf in two steps (LidarOdometry::prepare): prepareScan reads only the configuration
  /// (and the given poses, set before the first scan), so scans can be prepared on a third thread
  /// ahead of odometryOf(prepared), which gives what odometryOf gives.
  PreparedScan prepareScan(double stamp, std::shared_ptr<const PointCloud> scan_in_base,
                           std::shared_ptr<const std::vector<float>> point_offsets_s) const;
  ScanOdometry odometryOf(const PreparedScan& scan);

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
  const Backend& backend() const { return backend_.backend(); }
  const KeyframeClouds& keyframeClouds() const { return backend_.keyframeClouds(); }
  /// The sensor's position in the base frame: where the keyframe clouds' rays start.
  const Eigen::Vector3d& sensorInBase() const { return sensor_in_base_; }
  const StageTimes& stageTimes() const { return stage_times_; }
  /// Total backend optimisation time (t_FGO; wall, and the CPU time of its thread) and
  /// loop-detection time (t_LD) in seconds.
  double fgoSeconds() const { return backend().totalOptimizationMs() / 1e3; }
  double fgoCpuSeconds() const { return backend().totalOptimizationCpuMs() / 1e3; }
  double ldSeconds() const { return loops_.detector().stats().total_ms / 1e3; }
  const LoopDetector& loopDetector() const { return loops_.detector(); }
  const TraversableMap& traversableMap() const { return rooms_.traversableMap(); }

 private:
  void processKeyframe(const OdometryResult& odom, ScanOutcome* outcome);
  /// Hands updated rooms to the backend; a room re-detection triggers CoSG-LCD (Sec. III-D).
  void applyRooms(const RoomUpdate& update, ScanOutcome* outcome);
  void applyLoops(const std::vector<RoomLoopDetection>& detections, ScanOutcome* outcome);
  /// The backend's current keyframe poses (map frame).
  std::map<uint32_t, Pose3> keyframePoses() const;

  PipelineConfig config_;
  LidarOdometry odometry_estimator_;
  std::unique_ptr<ExternalOdometry> given_poses_;  // set: odometry from given poses
  Eigen::Vector3d sensor_in_base_;                 // wall extraction's viewpoint
  GroundLeveller leveller_;
  WallExtractor wall_extractor_;
  TraversabilityMapper traversability_mapper_;
  BackendSession backend_;
  RoomSegmentationSession rooms_;
  LoopClosureSession loops_;
  std::vector<uint32_t> keyframe_ids_;  // in arrival (= stamp) order
  std::vector<double> keyframe_stamps_;
  PipelineStats stats_;
  Trajectory odometry_;
  StageTimes stage_times_;
};

}  // namespace tacs
