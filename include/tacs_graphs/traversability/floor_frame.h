// The ground frame under a base that is not on the floor: a hand-held sensor, a backpack rig or a
// high mount whose base frame is the sensor itself, tilted with the operator's hand. Traversability
// (and the rooms built on it) assume a gravity-aligned base on the floor (paper Sec. III-A); this
// frame is that base: the keyframe's pose levelled by its map roll and pitch, lowered onto the
// floor plane found below it.
#pragma once

#include <optional>

#include "tacs_graphs/common/types.h"

namespace tacs {

struct FloorFrame {
  Pose3 T_base_floor = Pose3::Identity();  // the floor frame in the base frame
  double height_m = 0.0;                   // the base's height above the floor
  bool floor_seen = false;                 // false: the last known height was used
};

/// `cloud_in_base`: the keyframe cloud; `T_map_base`: its pose in a levelled map. The floor is
/// the largest plane at least 0.3 m below the base within 10 deg of level; when none is seen,
/// `last_height_m` (if any) stands in, else the base itself is taken as on the floor.
FloorFrame floorFrameUnder(const PointCloud& cloud_in_base, const Pose3& T_map_base,
                           std::optional<double> last_height_m);

/// The floor frames of a run's keyframes in order: the last height seen stands in where the floor
/// is not seen. The offline pipeline and the nodes (traversability, wall_extraction) each keep
/// one and get the same frames from the same keyframes.
class FloorTracker {
 public:
  FloorFrame next(const PointCloud& cloud_in_base, const Pose3& T_map_base);

 private:
  std::optional<double> last_height_m_;
};

}  // namespace tacs
