#include "tacs_graphs/pipeline/pipeline.h"

#include <algorithm>

#include "tacs_graphs/odometry/preprocess.h"

namespace tacs {

namespace {
PipelineConfig validated(const PipelineConfig& config) {
  config.validate();
  return config;
}
}  // namespace

Pipeline::Pipeline(const PipelineConfig& config)
    : config_(validated(config)),
      odometry_estimator_(config_.odometry),
      wall_extractor_(config_.walls.extraction),
      backend_(config_.backend, config_.walls.association) {}

ScanOutcome Pipeline::processScan(double stamp, const PointCloud& scan_in_base) {
  ScanOutcome outcome;
  ++stats_.scans;
  const OdometryResult odom = odometry_estimator_.process(stamp, scan_in_base);
  stage_times_.add("odometry", odom.time_ms);
  if (!odom.ok) {
    ++stats_.rejected_scans;
    if (stats_.first_rejection.empty()) stats_.first_rejection = odom.error;
    outcome.error = odom.error;
    return outcome;
  }
  outcome.accepted = true;
  odometry_.push_back({stamp, odom.T_odom_base});
  if (odom.is_keyframe) processKeyframe(odom, &outcome);
  return outcome;
}

void Pipeline::processKeyframe(const OdometryResult& odom, ScanOutcome* outcome) {
  outcome->keyframe = true;
  outcome->keyframe_id = odom.keyframe_id;
  ++stats_.keyframes;
  // Kept for the map, the OctoMap and loop closure at the odometry's grid: a long run keeps
  // thousands of keyframes.
  keyframe_clouds_[odom.keyframe_id] = PointCloud::ConstPtr(new PointCloud(
      voxelDownsample(*odom.keyframe_cloud, config_.odometry.preprocess.voxel_size_m)));
  backend_.addKeyframe(odom.keyframe_id, odom.stamp, odom.T_odom_base, odom.information);

  // Walls (Sec. III-B-1) from the keyframe's downsampled scan, associated to map landmarks.
  const WallExtractionResult walls = wall_extractor_.extract(*odom.keyframe_cloud);
  stage_times_.add("walls", walls.time_ms);
  backend_.addWallObservations(odom.keyframe_id, walls.walls);
  outcome->walls = walls.walls.size();
  stats_.wall_observations += walls.walls.size();

  if (const auto report = backend_.optimizeIfDue()) {
    stage_times_.add("backend", report->time_ms);
    outcome->optimized = true;
  }
}

void Pipeline::finish() {
  if (stats_.keyframes == 0) return;
  const OptimizationReport report = backend_.optimize();
  stage_times_.add("backend", report.time_ms);
}

Trajectory Pipeline::keyframeTrajectory() const {
  Trajectory trajectory;
  for (const auto& [id, kf] : backend_.sceneGraph().keyframes) {
    trajectory.push_back({kf.stamp, kf.pose()});
  }
  std::sort(trajectory.begin(), trajectory.end(),
            [](const StampedPose& a, const StampedPose& b) { return a.stamp < b.stamp; });
  return trajectory;
}

}  // namespace tacs
