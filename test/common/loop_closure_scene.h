// Keyframes for loop-closure tests: scans of the synthetic box room (box_room.h) rendered at
// ground-truth poses, voxel-downsampled as the odometry's keyframe clouds are. The base frame is
// the sensor frame, 0.5 m above the floor.
#pragma once

#include <cstdint>

#include "common/box_room.h"
#include "tacs_graphs/loop_closure/loop_detector.h"
#include "tacs_graphs/odometry/preprocess.h"

namespace tacs::test {

/// A planar robot pose in the box room: x, y [m], yaw [deg].
inline Pose3 roomPose(double x, double y, double yaw_deg) {
  return poseFromXyzRpy(x, y, 0.5, 0.0, 0.0, yaw_deg * M_PI / 180.0);
}

/// The keyframe cloud seen from T_world_base (range-cropped, 0.2 m voxels), range noise `noise_m`.
inline PointCloud keyframeCloud(const BoxRoom& room, const Pose3& T_world_base, unsigned seed,
                                double noise_m = 0.01) {
  return preprocess(renderScan(room, T_world_base, seed, 16, 900, noise_m), PreprocessConfig());
}

/// Adds keyframe `id` seen from `truth` with the pose estimate `estimate`; stamp = id seconds.
inline void addRoomKeyframe(LoopDetector* detector, const BoxRoom& room, uint32_t id,
                            const Pose3& truth, const Pose3& estimate) {
  detector->addKeyframe(id, static_cast<double>(id), estimate, keyframeCloud(room, truth, id));
}

}  // namespace tacs::test
