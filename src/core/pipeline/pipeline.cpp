#include "tacs_graphs/pipeline/pipeline.h"

#include <pcl/common/transforms.h>

#include "tacs_graphs/odometry/preprocess.h"
#include "tacs_graphs/traversability/floor_frame.h"

namespace tacs {

namespace {
PipelineConfig validated(const PipelineConfig& config) {
  config.validate();
  return config;
}
}  // namespace

Pipeline::Pipeline(const PipelineConfig& config, const Pose3& T_base_sensor)
    : config_(validated(config)),
      odometry_estimator_(config_.odometry),
      wall_extractor_(config_.walls.extraction),
      sensor_in_base_(T_base_sensor.translation()),
      traversability_mapper_(config_.traversability),
      traversable_map_(config_.traversability),
      room_segmenter_(config_.rooms, config_.walls.axes, T_base_sensor),
      loop_detector_(config_.loop_closure),
      backend_(config_.backend, config_.walls.association),
      map_clouds_(config_.map_export.cloud_retention) {}

ScanOutcome Pipeline::processScan(double stamp, const PointCloud& scan_in_base,
                                  const std::vector<float>* point_offsets_s) {
  ScanOutcome outcome;
  ++stats_.scans;
  if (given_poses_ && !given_poses_->poseAt(stamp)) {
    ++stats_.scans_outside_poses;
    outcome.error = "no given pose at the scan's stamp";
    return outcome;
  }
  const OdometryResult odom =
      given_poses_ ? given_poses_->process(stamp, scan_in_base)
                   : odometry_estimator_.process(stamp, scan_in_base, point_offsets_s);
  stage_times_.add("odometry", odom.time_ms);
  stats_.deskewed_scans += odom.deskewed ? 1 : 0;
  stats_.odometry_recoveries += odom.recovered ? 1 : 0;
  outcome.recovered = odom.recovered;
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

void Pipeline::useGivenPoses(const Trajectory& poses) {
  constexpr double kSigmaXyzM = 0.02, kSigmaRotDeg = 0.5;
  given_poses_ =
      ExternalOdometry::fromTrajectory(config_.odometry, poses, kSigmaXyzM, kSigmaRotDeg);
}

void Pipeline::processKeyframe(const OdometryResult& odom, ScanOutcome* outcome) {
  const uint32_t id = odom.keyframe_id;
  outcome->keyframe = true;
  outcome->keyframe_id = id;
  ++stats_.keyframes;
  keyframe_ids_.push_back(id);
  keyframe_stamps_.push_back(odom.stamp);
  const PointCloud& cloud = *odom.keyframe_cloud;
  // Kept for the map, the OctoMap and loop closure at the odometry's grid: a long run keeps
  // thousands of keyframes.
  const PointCloud::ConstPtr coarse(
      new PointCloud(voxelDownsample(cloud, config_.odometry.preprocess.voxel_size_m)));
  backend_.addKeyframe(id, odom.stamp, odom.T_odom_base, odom.information);
  map_clouds_.add(id, coarse, backend_);
  const Pose3 T_map_base = backend_.keyframePose(id);

  // A base off the floor (hand-held): walls and terrain are read in the levelled floor frame.
  PointCloud in_floor;
  if (config_.traversability.find_floor_under_base) {
    const FloorFrame floor = floor_tracker_.next(cloud, T_map_base);
    base_to_floor_[id] = floor.T_base_floor;
    pcl::transformPointCloud(cloud, in_floor, floor.T_base_floor.inverse().matrix().cast<float>());
  }
  const bool levelled = config_.traversability.find_floor_under_base;
  const PointCloud& ground_cloud = levelled ? in_floor : cloud;

  // Walls (Sec. III-B-1), associated to the backend's landmarks.
  WallExtractionResult walls = extractWalls(id, ground_cloud);
  stage_times_.add("walls", walls.time_ms);
  backend_.addWallObservations(id, walls.walls, walls.seen_over);
  outcome->walls = walls.walls.size();
  stats_.wall_observations += walls.walls.size();

  // Traversable graph of the keyframe into the map (Sec. III-A, III-B-2); the voxel baseline
  // segments from the clouds instead.
  if (config_.rooms.method == RoomMethod::kTacs) {
    Stopwatch watch;
    const TraversabilityResult trav = traversability_mapper_.process(ground_cloud);
    traversable_map_.insert(trav.graph, groundPose(id), id);
    stage_times_.add("traversability", trav.time_ms + watch.elapsedMs());
  }

  loop_detector_.addKeyframe(id, odom.stamp, T_map_base, *coarse);
  const RoomSegmentationResult rooms = room_segmenter_.processKeyframe(
      id, groundPose(id), traversable_map_, backend_.wallMap(), &cloud);
  stage_times_.add("rooms", rooms.time_ms);
  applyRooms(rooms, id, outcome);
  if (config_.loop_closure.method == LoopMethod::kDistance) {
    applyLoops(loop_detector_.detectByDistance(id), outcome);
  }

  if (const auto report = backend_.optimizeIfDue()) {
    stage_times_.add("backend", report->time_ms);
    outcome->optimized = true;
    // A loop moves the map: rooms must see the corrected free space. Otherwise only the loop
    // detector's pose estimates follow (cheap).
    propagatePoses(loop_since_pose_update_);
  }
}

void Pipeline::applyRooms(const RoomSegmentationResult& result, uint32_t query_keyframe,
                          ScanOutcome* outcome) {
  outcome->rooms += result.observations.size();
  stats_.room_observations += result.observations.size();
  for (const RoomAssociation& a : result.associations) {
    const auto room = room_segmenter_.rooms().find(a.room_id);
    if (room == room_segmenter_.rooms().end()) continue;
    for (uint32_t absorbed : a.absorbed) backend_.removeRoom(absorbed);
    backend_.setRoom(room->second);
    for (const auto& [mapped, observed] : a.wall_to_wall) backend_.addWallToWall(mapped, observed);
    if (a.created) continue;
    ++stats_.room_redetections;
    const uint32_t query = cosgQueryKeyframe(room->second.room.keyframe_ids, query_keyframe);
    if (config_.loop_closure.method == LoopMethod::kCosg && backend_.hasKeyframe(query)) {
      applyLoops(loop_detector_.detectInRoom(query, room->second.room.keyframe_ids), outcome);
    }
  }
}

void Pipeline::applyLoops(const LoopDetection& detection, ScanOutcome* outcome) {
  stage_times_.add("loop_detection", detection.time_ms);
  for (const LoopClosure& loop : detection.loops) {
    backend_.addLoopClosure(loop.from, loop.to, loop.T_from_to, loop.information, loop.score);
    ++outcome->loops;
    loop_since_pose_update_ = true;
  }
}

void Pipeline::propagatePoses(bool rebuild_traversable_map) {
  std::map<uint32_t, Pose3> poses;
  for (uint32_t id : keyframe_ids_) poses[id] = backend_.keyframePose(id);
  loop_detector_.updatePoses(poses);
  if (rebuild_traversable_map && config_.rooms.method == RoomMethod::kTacs) {
    Stopwatch watch;
    for (auto& [id, pose] : poses) pose = groundPose(id);
    traversable_map_.updatePoses(poses);
    stage_times_.add("traversability", watch.elapsedMs());
  }
  if (rebuild_traversable_map) loop_since_pose_update_ = false;
}

WallExtractionResult Pipeline::extractWalls(uint32_t id, const PointCloud& ground_cloud) {
  const auto floor = base_to_floor_.find(id);
  if (floor == base_to_floor_.end()) return wall_extractor_.extract(ground_cloud, sensor_in_base_);
  return wall_extractor_.extractInFrame(ground_cloud, floor->second, sensor_in_base_);
}

Pose3 Pipeline::groundPose(uint32_t id) const {
  const auto floor = base_to_floor_.find(id);
  const Pose3 T_map_base = backend_.keyframePose(id);
  return floor == base_to_floor_.end() ? T_map_base : T_map_base * floor->second;
}

void Pipeline::finish() {
  if (stats_.keyframes == 0) return;
  ScanOutcome outcome;
  const RoomSegmentationResult rooms = room_segmenter_.finish(traversable_map_, backend_.wallMap());
  stage_times_.add("rooms", rooms.time_ms);
  applyRooms(rooms, keyframe_ids_.back(), &outcome);
  const OptimizationReport report = backend_.optimize();
  stage_times_.add("backend", report.time_ms);
}

Trajectory Pipeline::keyframeTrajectory() const {
  // Keyframes arrive in stamp order (the odometry rejects stamps that go back).
  Trajectory trajectory;
  trajectory.reserve(keyframe_ids_.size());
  for (size_t k = 0; k < keyframe_ids_.size(); ++k) {
    trajectory.push_back({keyframe_stamps_[k], backend_.keyframePose(keyframe_ids_[k])});
  }
  return trajectory;
}

}  // namespace tacs
