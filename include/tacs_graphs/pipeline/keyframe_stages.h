// The per-keyframe stages that need nothing but the keyframe itself: the floor frame under the
// base, wall extraction (paper Sec. III-B-1) and traversability (Sec. III-A). The wall_extraction
// and traversability nodes each run their stage on the keyframes they receive; the offline
// Pipeline runs both on the same levelled keyframe (docs/DESIGN.md, "One wiring").
#pragma once

#include <Eigen/Core>

#include "tacs_graphs/common/types.h"
#include "tacs_graphs/traversability/floor_frame.h"
#include "tacs_graphs/traversability/traversability_mapper.h"
#include "tacs_graphs/walls/wall_extractor.h"

namespace tacs {

/// A keyframe cloud with the ground frame it is read in: the base itself (a robot on the floor),
/// or the levelled floor frame under a base carried off the floor (hand-held, high mount).
struct LevelledKeyframe {
  PointCloud::ConstPtr cloud_in_ground;     // the cloud in the ground frame
  Pose3 T_base_ground = Pose3::Identity();  // the ground frame in the base frame
  bool levelled = false;                    // false: ground frame = base frame
};

/// Finds the ground frame of each keyframe in order (traversability.find_floor_under_base).
class GroundLeveller {
 public:
  explicit GroundLeveller(bool find_floor_under_base) : enabled_(find_floor_under_base) {}
  /// `T_map_base`: the keyframe's current map pose, whose roll and pitch level the floor (the
  /// map is gravity-aligned by its vertical walls; an odometry frame need not be).
  LevelledKeyframe level(const PointCloud::ConstPtr& cloud_in_base, const Pose3& T_map_base);

 private:
  bool enabled_;
  FloorTracker tracker_;
};

/// Walls and seen-over surfaces of a keyframe, in the base frame. Seen from the sensor: the
/// low-surface and seen-over tests measure rays from `sensor_in_base`.
WallExtractionResult extractKeyframeWalls(const WallExtractor& extractor,
                                          const LevelledKeyframe& keyframe,
                                          const Eigen::Vector3d& sensor_in_base);

/// The traversable graph, ground and obstacle points of a keyframe, in its ground frame
/// (keyframe.T_base_ground): the graph's heights are heights above the floor there.
TraversabilityResult keyframeTraversability(const TraversabilityMapper& mapper,
                                            const LevelledKeyframe& keyframe);

}  // namespace tacs
