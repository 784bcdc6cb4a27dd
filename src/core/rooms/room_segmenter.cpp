#include "tacs_graphs/rooms/room_segmenter.h"

#include <algorithm>
#include <utility>

#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/rooms/room_bounds.h"

namespace tacs {

namespace {

const RoomsConfig& validated(const RoomsConfig& config) {
  config.validate();
  return config;
}

}  // namespace

RoomSegmenter::RoomSegmenter(const RoomsConfig& config, const DominantAxesConfig& axes,
                             const Pose3& T_base_sensor)
    : config_(validated(config)),
      axes_config_(axes),
      T_base_sensor_(T_base_sensor),
      tacs_(config.tacs),
      voxel_(config.voxel),
      room_map_(config.merging) {
  axes_config_.validate();
}

void RoomSegmenter::addRegion(std::vector<Eigen::Vector3d> points,
                              std::vector<uint32_t> keyframe_ids,
                              const std::vector<Eigen::Vector3d>& path, const WallMap& walls,
                              const DominantAxes& axes, RoomSegmentationResult* result) {
  if (!axes.valid) {
    result->rejected.push_back("building axes unknown (too few walls)");
    return;
  }
  // Free-standing furniture bounds no room in the paper's method (rooms/room_bounds.h).
  const bool anchored_only = freeStandingFurnitureBoundsNoRoom(config_);
  const std::map<uint32_t, WallLandmark> anchored =
      anchored_only ? roomBoundingPlanes(walls, config_.extraction)
                    : std::map<uint32_t, WallLandmark>{};
  const std::map<uint32_t, WallLandmark>& bounding = anchored_only ? anchored : walls.landmarks();
  // Doorways let a room's wall run on past its door, so what leaked through the door stays out.
  const std::vector<Doorway> doorways = findDoorways(walls.landmarks(), config_.tacs);
  // Doors in the room-bounding walls only (not gaps between free-standing furniture): what an
  // unbounded region may not reach its room through.
  const std::vector<Doorway> bounding_doorways = findDoorways(bounding, config_.tacs);
  RoomExtractionResult extracted =
      extractRoom(points, bounding, axes, config_.extraction, doorways);
  // A TACS region that ran through a doorway unnoticed holds two mapped rooms a wall separates;
  // merging would fold them into one.
  const auto spans_rooms = [&](const RoomExtractionResult& r) {
    return config_.method == RoomMethod::kTacs && r.found &&
           room_map_.spansSeparateRooms(r.room, walls.landmarks());
  };
  bool spans = spans_rooms(extracted);
  const double radius = config_.tacs.path_retry_radius;
  if ((!extracted.found || spans) && radius > 0.0 && !path.empty()) {
    // A region around a corner of two corridors lies half in each: no facing pair holds most of
    // it. The free space near the robot's path is the corridor it drove along (also the part of
    // a region spanning two rooms that the robot drove through).
    std::vector<Eigen::Vector3d> near;
    for (const auto& p : points) {
      const bool close = std::any_of(path.begin(), path.end(), [&](const Eigen::Vector3d& q) {
        return (p - q).head<2>().squaredNorm() <= radius * radius;
      });
      if (close) near.push_back(p);
    }
    if (near.size() < points.size()) {
      RoomExtractionResult retried =
          extractRoom(near, bounding, axes, config_.extraction, doorways);
      if (retried.found && !spans_rooms(retried)) {
        extracted = std::move(retried);
        spans = false;
      }
    }
  }
  if (anchored_only && joinedAHall(extracted, points, keyframe_ids, walls, bounding,
                                   bounding_doorways, axes, result))
    return;
  if (!extracted.found) {
    // A region only free-standing furniture bounds (an aisle between racks) is part of the room
    // it opens into, mapped from where that room's walls were seen.
    if (anchored_only && bounding.size() < walls.landmarks().size() &&
        extractRoom(points, walls.landmarks(), axes, config_.extraction).found) {
      RoomObservation region;
      region.free_space = std::move(points);
      region.keyframe_ids = std::move(keyframe_ids);
      // The room it opens into may be mapped later (its walls seen from elsewhere): kept until
      // then.
      unbounded_.push_back(std::move(region));
      joinUnboundedRegions(walls, bounding, bounding_doorways, result);
      return;
    }
    result->rejected.push_back(extracted.reason);
    return;
  }
  if (spans) {
    result->rejected.push_back("region spans mapped rooms a wall separates (a missed doorway)");
    return;
  }
  extracted.room.keyframe_ids = std::move(keyframe_ids);
  const bool by_center_distance = config_.method == RoomMethod::kVoxel &&
                                  config_.voxel.merging == VoxelMerging::kCenterDistance;
  const RoomAssociation a =
      by_center_distance ? room_map_.addByCenterDistance(extracted.room, walls.landmarks(),
                                                         config_.voxel.merge_distance)
                         : room_map_.addObservation(extracted.room, walls.landmarks(), &bounding);
  result->observations.push_back(std::move(extracted.room));
  result->associations.push_back(a);
  if (!unbounded_.empty()) joinUnboundedRegions(walls, bounding, bounding_doorways, result);
}

bool RoomSegmenter::joinedAHall(const RoomExtractionResult& extracted,
                                const std::vector<Eigen::Vector3d>& points,
                                const std::vector<uint32_t>& keyframe_ids, const WallMap& walls,
                                const std::map<uint32_t, WallLandmark>& bounding,
                                const std::vector<Doorway>& bounding_doorways,
                                const DominantAxes& axes, RoomSegmentationResult* result) {
  // A corridor's walls are close. A hall's two long walls around a region that furniture rows
  // close on the other axis (beside a supermarket's gondolas) make it part of the hall when the
  // hall is mapped (a room sharing one of those walls); else it stands for the hall.
  if (!extracted.found || extracted.room.kind != RoomKind::kCorridor ||
      extracted.corridor_width <= config_.extraction.max_corridor_width) {
    return false;
  }
  const RoomExtractionResult closed =
      extractRoom(points, walls.landmarks(), axes, config_.extraction);
  if (!closed.found || closed.room.kind != RoomKind::kRoom) return false;
  RoomObservation region = extracted.room;
  region.keyframe_ids = keyframe_ids;
  auto joined = room_map_.addUnbounded(region, walls.landmarks(), bounding, bounding_doorways);
  if (!joined) return false;
  result->observations.push_back(std::move(region));
  result->associations.push_back(std::move(*joined));
  return true;
}

void RoomSegmenter::joinUnboundedRegions(const WallMap& walls,
                                         const std::map<uint32_t, WallLandmark>& bounding,
                                         const std::vector<Doorway>& doorways,
                                         RoomSegmentationResult* result) {
  for (auto it = unbounded_.begin(); it != unbounded_.end();) {
    if (auto joined = room_map_.addUnbounded(*it, walls.landmarks(), bounding, doorways)) {
      result->observations.push_back(std::move(*it));
      result->associations.push_back(std::move(*joined));
      it = unbounded_.erase(it);
    } else {
      ++it;
    }
  }
}

void RoomSegmenter::clusterVoxels(const WallMap& walls, const DominantAxes& axes,
                                  RoomSegmentationResult* result) {
  keyframes_since_clustering_ = 0;
  for (auto& cluster : voxel_.clusters()) {
    addRegion(std::move(cluster.points), std::move(cluster.keyframe_ids), {}, walls, axes, result);
  }
}

RoomSegmentationResult RoomSegmenter::processKeyframe(uint32_t keyframe_id, const Pose3& T_map_base,
                                                      const TraversableMap& map,
                                                      const WallMap& walls,
                                                      const PointCloud* cloud_in_base) {
  Stopwatch watch;
  RoomSegmentationResult result;
  if (config_.method == RoomMethod::kNone) return result;
  room_map_.refreshWalls(walls.landmarks());
  const DominantAxes axes = estimateDominantAxes(walls, axes_config_);
  if (config_.method == RoomMethod::kVoxel) {
    if (!cloud_in_base) {
      result.rejected.push_back("voxel method: no keyframe cloud given");
    } else {
      voxel_.integrate(keyframe_id, *cloud_in_base, T_map_base, T_base_sensor_.translation());
      if (++keyframes_since_clustering_ >= config_.voxel.update_every_keyframes) {
        clusterVoxels(walls, axes, &result);
      }
    }
  } else {
    TacsFreeSpace::StepResult step =
        tacs_.step(keyframe_id, T_map_base.translation(), map, walls.landmarks());
    result.robot_inside = step.inside;
    result.doorways = step.doorways;
    for (auto& region : step.finished) {
      addRegion(std::move(region.points), std::move(region.keyframe_ids), region.keyframe_positions,
                walls, axes, &result);
    }
  }
  result.time_ms = watch.elapsedMs();
  return result;
}

RoomSegmentationResult RoomSegmenter::finish(const TraversableMap& map, const WallMap& walls) {
  Stopwatch watch;
  RoomSegmentationResult result;
  if (config_.method == RoomMethod::kNone) return result;
  room_map_.refreshWalls(walls.landmarks());
  const DominantAxes axes = estimateDominantAxes(walls, axes_config_);
  if (config_.method == RoomMethod::kVoxel) {
    clusterVoxels(walls, axes, &result);
  } else if (auto region = tacs_.flush(map, walls.landmarks())) {
    addRegion(std::move(region->points), std::move(region->keyframe_ids),
              region->keyframe_positions, walls, axes, &result);
  }
  result.time_ms = watch.elapsedMs();
  return result;
}

void RoomSegmenter::writeTo(SceneGraph* graph) const {
  for (const auto& [id, room] : rooms()) {
    graph->rooms[id] = room.toNode();
    for (uint32_t kf : room.room.keyframe_ids) {
      auto it = graph->keyframes.find(kf);
      if (it != graph->keyframes.end()) it->second.room_id = static_cast<int>(id);
    }
  }
}

}  // namespace tacs
