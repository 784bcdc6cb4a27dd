// The whole SLAM pipeline run synchronously in one thread of control, as tacs_offline and the
// benchmarks use it: odometry -> keyframes -> walls -> backend (the same core classes the ROS nodes
// run, DESIGN.md "Two ways to run the same core"). Deterministic for a given input.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "tacs_graphs/backend/backend.h"
#include "tacs_graphs/backend/map_export.h"
#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/odometry/lidar_odometry.h"
#include "tacs_graphs/pipeline/pipeline_config.h"
#include "tacs_graphs/walls/wall_extractor.h"

namespace tacs {

/// What happened to one scan.
struct ScanOutcome {
  bool accepted = false;
  std::string error;  // why the scan was rejected (accepted == false)
  bool keyframe = false;
  uint32_t keyframe_id = 0;
  size_t walls = 0;        // wall observations of the keyframe
  bool optimized = false;  // the backend optimised after this scan
};

/// Counters of a run (timing.json).
struct PipelineStats {
  size_t scans = 0;
  size_t rejected_scans = 0;
  size_t keyframes = 0;
  size_t wall_observations = 0;
  std::string first_rejection;  // the reason of the first rejected scan, for the log
};

class Pipeline {
 public:
  /// Validates the configuration (throws ConfigError).
  explicit Pipeline(const PipelineConfig& config);

  /// Processes one scan given in the base frame (the caller applies the sensor extrinsic). Never
  /// throws on bad data: the scan is rejected with a reason and the state is kept.
  ScanOutcome processScan(double stamp, const PointCloud& scan_in_base);

  /// Final optimisation after the last scan.
  void finish();

  const PipelineConfig& config() const { return config_; }
  const PipelineStats& stats() const { return stats_; }
  /// Odom-frame pose of every accepted scan.
  const Trajectory& odometryTrajectory() const { return odometry_; }
  /// Optimised keyframe poses in the map frame, by stamp.
  Trajectory keyframeTrajectory() const;
  SceneGraph sceneGraph() const { return backend_.sceneGraph(); }
  const Backend& backend() const { return backend_; }
  const KeyframeClouds& keyframeClouds() const { return keyframe_clouds_; }
  const StageTimes& stageTimes() const { return stage_times_; }
  /// Total backend optimisation time (t_FGO) and loop-detection time (t_LD) in seconds.
  double fgoSeconds() const { return backend_.totalOptimizationMs() / 1e3; }
  double ldSeconds() const { return ld_ms_ / 1e3; }

 private:
  void processKeyframe(const OdometryResult& odom, ScanOutcome* outcome);

  PipelineConfig config_;
  LidarOdometry odometry_estimator_;
  WallExtractor wall_extractor_;
  Backend backend_;
  PipelineStats stats_;
  Trajectory odometry_;
  KeyframeClouds keyframe_clouds_;
  StageTimes stage_times_;
  double ld_ms_ = 0.0;
};

}  // namespace tacs
