#include "tacs_graphs/pipeline/room_segmentation_session.h"

#include <algorithm>
#include <cmath>

namespace tacs {
namespace {

PipelineConfig validated(const PipelineConfig& config) {
  config.validate();
  return config;
}

double rotationDeg(const Pose3& a, const Pose3& b) {
  const Eigen::AngleAxisd delta(a.rotation().transpose() * b.rotation());
  return std::abs(delta.angle()) * 180.0 / M_PI;
}

}  // namespace

RoomSegmentationSession::RoomSegmentationSession(const PipelineConfig& config,
                                                 const RoomSegmentationOptions& options,
                                                 const std::optional<Pose3>& T_base_sensor)
    : config_(validated(config)),
      options_(options),
      traversable_map_(config_.traversability),
      segmenter_(config_.rooms, config_.walls.axes,
                 T_base_sensor.value_or(config_.frames.baseToSensor())),
      wall_map_(config_.walls.association) {}

RoomSegmentationSession::Pending& RoomSegmentationSession::pending(uint32_t id, double stamp,
                                                                   const Pose3& T_odom_base) {
  poses_.addOdometryPose(id, T_odom_base);
  newest_id_ = std::max(newest_id_, id);
  Pending& p = pending_[id];
  p.stamp = stamp;
  return p;
}

void RoomSegmentationSession::addGraph(uint32_t id, double stamp, const Pose3& T_odom_base,
                                       TravGraph graph, const Pose3& T_base_ground) {
  if (needsClouds() || inserted_poses_.count(id) > 0) return;  // voxel method, or segmented
  Pending& p = pending(id, stamp, T_odom_base);
  p.graph = std::move(graph);
  p.has_graph = true;
  p.T_base_ground = T_base_ground;
}

Pose3 RoomSegmentationSession::groundPose(uint32_t id, const Pose3& T_map_base) const {
  const auto it = base_to_ground_.find(id);
  return it == base_to_ground_.end() ? T_map_base : T_map_base * it->second;
}

void RoomSegmentationSession::addCloud(uint32_t id, double stamp, const Pose3& T_odom_base,
                                       PointCloud::ConstPtr cloud) {
  if (!needsClouds() || inserted_poses_.count(id) > 0) return;
  pending(id, stamp, T_odom_base).cloud = std::move(cloud);
}

void RoomSegmentationSession::setSceneGraph(const SceneGraph& graph,
                                            const std::map<uint32_t, uint32_t>& wall_observations) {
  poses_.setGraph(graph);
  wall_map_ = wallMapFromSceneGraph(graph, wall_observations, config_.walls.association);
  reposeIfMoved();
}

void RoomSegmentationSession::setMap(const std::map<uint32_t, Pose3>& T_map_base,
                                     const WallMap& walls) {
  poses_.setPoses(T_map_base);
  wall_map_ = walls;
  reposeIfMoved();
}

void RoomSegmentationSession::reposeIfMoved() {
  std::map<uint32_t, Pose3> moved;
  bool noticeable = false;
  for (const auto& [id, inserted] : inserted_poses_) {
    const auto now = poses_.optimised(id);
    if (!now) continue;
    moved[id] = *now;
    noticeable =
        noticeable ||
        (now->translation() - inserted.translation()).norm() > options_.repose_distance_m ||
        rotationDeg(*now, inserted) > options_.repose_angle_deg;
  }
  if (!noticeable) return;
  // Rebuilding the map is the costly part: only when the backend moved keyframes (a loop, or
  // walls and rooms pulling on them), as the offline pipeline does after a loop.
  if (!needsClouds()) {
    std::map<uint32_t, Pose3> ground;
    for (const auto& [id, pose] : moved)
      ground.emplace_hint(ground.end(), id, groundPose(id, pose));
    traversable_map_.updatePoses(ground);
  }
  for (const auto& [id, pose] : moved) inserted_poses_[id] = pose;
  ++reposes_;
}

bool RoomSegmentationSession::hasInputs(const Pending& p) const {
  return needsClouds() ? static_cast<bool>(p.cloud) : p.has_graph;
}

std::vector<RoomUpdate> RoomSegmentationSession::processReady() {
  std::vector<RoomUpdate> updates;
  while (!pending_.empty()) {
    const auto it = pending_.begin();
    const uint32_t id = it->first;
    const bool stale = newest_id_ > id + options_.max_wait_keyframes;
    const bool placed = poses_.optimised(id).has_value();
    if (!hasInputs(it->second)) {
      if (!stale) break;
      pending_.erase(it);  // its graph or cloud never came: segment the others
      continue;
    }
    if (!placed && !stale) break;
    const std::optional<Pose3> T_map_base = poses_.mapPose(id);
    const Pending p = std::move(it->second);
    pending_.erase(it);
    if (!T_map_base) continue;
    RoomUpdate update = segment(id, p, *T_map_base);
    if (!update.rooms.empty() || !update.rejected.empty()) updates.push_back(std::move(update));
  }
  return updates;
}

RoomUpdate RoomSegmentationSession::segment(uint32_t id, const Pending& p,
                                            const Pose3& T_map_base) {
  // The traversable graph and the robot's position are read in the keyframe's ground frame.
  if (!p.T_base_ground.isApprox(Pose3::Identity())) base_to_ground_[id] = p.T_base_ground;
  const Pose3 T_map_ground = groundPose(id, T_map_base);
  if (!needsClouds()) traversable_map_.insert(p.graph, T_map_ground, id);
  inserted_poses_[id] = T_map_base;
  last_stamp_ = std::max(last_stamp_, p.stamp);
  ++segmented_;
  const RoomSegmentationResult result =
      needsClouds()
          ? segmenter_.processKeyframe(id, T_map_base, traversable_map_, wall_map_, p.cloud.get())
          : segmenter_.processKeyframe(id, T_map_ground, traversable_map_, wall_map_);
  return toUpdate(id, p.stamp, result);
}

RoomUpdate RoomSegmentationSession::finish() {
  const uint32_t last = inserted_poses_.empty() ? 0 : inserted_poses_.rbegin()->first;
  if (segmented_ == 0) return toUpdate(last, last_stamp_, {});
  return toUpdate(last, last_stamp_, segmenter_.finish(traversable_map_, wall_map_));
}

RoomUpdate RoomSegmentationSession::toUpdate(uint32_t id, double stamp,
                                             const RoomSegmentationResult& result) const {
  RoomUpdate update;
  update.keyframe_id = id;
  update.stamp = stamp;
  update.rejected = result.rejected;
  for (const RoomAssociation& a : result.associations) {
    const auto room = segmenter_.rooms().find(a.room_id);
    if (room != segmenter_.rooms().end()) update.rooms.emplace_back(room->second, a);
  }
  return update;
}

}  // namespace tacs
