#include "tacs_graphs/pipeline/pipeline.h"

#include "tacs_graphs/odometry/preprocess.h"

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
      sensor_in_base_(T_base_sensor.translation()),
      leveller_(config_.traversability.find_floor_under_base),
      wall_extractor_(config_.walls.extraction),
      traversability_mapper_(config_.traversability),
      backend_(config_,
               [] {
                 BackendSessionOptions options;
                 options.keep_journal = false;  // one process that never restarts
                 return options;
               }()),
      rooms_(config_, RoomSegmentationOptions(), T_base_sensor),
      loops_(config_.loop_closure) {}

ScanOutcome Pipeline::processScan(double stamp, const PointCloud& scan_in_base,
                                  const std::vector<float>* point_offsets_s) {
  return takeOdometry(odometryOf(stamp, scan_in_base, point_offsets_s));
}

ScanOdometry Pipeline::odometryOf(double stamp, const PointCloud& scan_in_base,
                                  const std::vector<float>* point_offsets_s) {
  ScanOdometry scan;
  if (given_poses_ && !given_poses_->poseAt(stamp)) {
    scan.outside_given_poses = true;
    return scan;
  }
  scan.odometry = given_poses_ ? given_poses_->process(stamp, scan_in_base)
                               : odometry_estimator_.process(stamp, scan_in_base, point_offsets_s);
  return scan;
}

PreparedScan Pipeline::prepareScan(
    double stamp, std::shared_ptr<const PointCloud> scan_in_base,
    std::shared_ptr<const std::vector<float>> point_offsets_s) const {
  if (!given_poses_) {
    return odometry_estimator_.prepare(stamp, std::move(scan_in_base), std::move(point_offsets_s));
  }
  PreparedScan scan;  // the given poses need the scan only
  scan.stamp = stamp;
  scan.raw = std::move(scan_in_base);
  return scan;
}

ScanOdometry Pipeline::odometryOf(const PreparedScan& prepared) {
  if (given_poses_) return odometryOf(prepared.stamp, *prepared.raw);
  ScanOdometry scan;
  scan.odometry = odometry_estimator_.process(prepared);
  return scan;
}

ScanOutcome Pipeline::takeOdometry(const ScanOdometry& scan) {
  ScanOutcome outcome;
  ++stats_.scans;
  if (scan.outside_given_poses) {
    ++stats_.scans_outside_poses;
    outcome.error = "no given pose at the scan's stamp";
    return outcome;
  }
  const OdometryResult& odom = scan.odometry;
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
  odometry_.push_back({odom.stamp, odom.T_odom_base});
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
  const PointCloud::ConstPtr cloud = odom.keyframe_cloud;
  // Kept for the map, the OctoMap and loop closure at the odometry's grid: a long run keeps
  // thousands of keyframes.
  const PointCloud::ConstPtr coarse(
      new PointCloud(voxelDownsample(*cloud, config_.odometry.preprocess.voxel_size_m)));
  backend_.addKeyframe(id, odom.stamp, odom.T_odom_base, odom.information, coarse);

  // Walls (Sec. III-B-1), associated to the backend's landmarks; a base off the floor
  // (hand-held) is read in the floor frame levelled by the keyframe's map attitude.
  const LevelledKeyframe levelled = leveller_.level(cloud, backend().keyframePose(id));
  const WallExtractionResult walls =
      extractKeyframeWalls(wall_extractor_, levelled, sensor_in_base_);
  stage_times_.add("walls", walls.time_ms);
  backend_.addWalls(id, {walls.walls, walls.seen_over});
  outcome->walls = walls.walls.size();
  stats_.wall_observations += walls.walls.size();

  // Traversable graph of the keyframe for the rooms (Sec. III-A, III-B-2); the voxel baseline
  // segments from the clouds instead.
  if (rooms_.needsClouds()) {
    rooms_.addCloud(id, odom.stamp, odom.T_odom_base, cloud);
  } else {
    TraversabilityResult trav = keyframeTraversability(traversability_mapper_, levelled);
    stage_times_.add("traversability", trav.time_ms);
    rooms_.addGraph(id, odom.stamp, odom.T_odom_base, std::move(trav.graph));
  }
  applyLoops(loops_.addKeyframe(id, odom.stamp, odom.T_odom_base, *coarse), outcome);

  // Rooms read the backend's poses and walls, as the node reads the published scene graph; the
  // traversable map follows keyframes the backend moved noticeably.
  Stopwatch watch;
  rooms_.setMap(keyframePoses(), backend_.backend().wallMap());
  const std::vector<RoomUpdate> updates = rooms_.processReady();
  stage_times_.add("rooms", watch.elapsedMs());
  for (const RoomUpdate& update : updates) applyRooms(update, outcome);

  if (const auto report = backend_.optimizeIfDue()) {
    stage_times_.add("backend", report->time_ms);
    outcome->optimized = true;
    loops_.setGraphPoses(keyframePoses());
  }
}

void Pipeline::applyRooms(const RoomUpdate& update, ScanOutcome* outcome) {
  outcome->rooms += update.rooms.size();
  stats_.room_observations += update.rooms.size();
  for (const auto& [room, association] : update.rooms) {
    backend_.takeRoom(room, association.absorbed, association.wall_to_wall);
    if (association.created) continue;
    ++stats_.room_redetections;
    applyLoops(loops_.roomRedetected(static_cast<int>(room.id), room.room.keyframe_ids,
                                     update.keyframe_id),
               outcome);
  }
}

void Pipeline::applyLoops(const std::vector<RoomLoopDetection>& detections, ScanOutcome* outcome) {
  for (const RoomLoopDetection& found : detections) {
    stage_times_.add("loop_detection", found.detection.time_ms);
    for (const LoopClosure& loop : found.detection.loops) {
      backend_.addLoop(loop);
      ++outcome->loops;
    }
  }
}

std::map<uint32_t, Pose3> Pipeline::keyframePoses() const {
  std::map<uint32_t, Pose3> poses;
  for (uint32_t id : keyframe_ids_) poses.emplace_hint(poses.end(), id, backend().keyframePose(id));
  return poses;
}

void Pipeline::finish() {
  if (stats_.keyframes == 0) return;
  ScanOutcome outcome;
  Stopwatch watch;
  const RoomUpdate last = rooms_.finish();
  stage_times_.add("rooms", watch.elapsedMs());
  applyRooms(last, &outcome);
  const OptimizationReport report = backend_.optimize();
  stage_times_.add("backend", report.time_ms);
}

Trajectory Pipeline::keyframeTrajectory() const {
  // Keyframes arrive in stamp order (the odometry rejects stamps that go back).
  Trajectory trajectory;
  trajectory.reserve(keyframe_ids_.size());
  for (size_t k = 0; k < keyframe_ids_.size(); ++k) {
    trajectory.push_back({keyframe_stamps_[k], backend().keyframePose(keyframe_ids_[k])});
  }
  return trajectory;
}

}  // namespace tacs
