// The traversability test scene and a helper that scans it from a robot pose.
#pragma once

#include "common/synthetic_lidar.h"
#include "tacs_graphs/traversability/traversability_mapper.h"

namespace tacs::test {

constexpr double kSensorHeight = 0.8;

// Robot floor at z = 0. Wall along y = 4 with doorways x in [0.6, 1.4] (0.8 m) and
// [3.6, 3.6 + second_door] ; room 2 beyond it. For y < 4: drop-off to z = -1 for x > 6, y < 1;
// a 0.17 m step up for x > 6, 1 < y < 4; a 0.9 m half wall at x = -3 with floor beyond.
inline Scene testScene(double second_door = 1.0) {
  Scene s;
  s.floor(-6, -6, 6, 4, 0.0);                // main room
  s.floor(-6, 4, 10, 8, 0.0);                // room 2 beyond the wall
  s.floor(6, -6, 10, 1, -1.0);               // lower level beyond the drop-off
  s.floor(6, 1, 10, 4, 0.17);                // raised platform behind a step
  s.add(6, 1, -1.1, 10, 1.01, 0.17, false);  // its side face toward the lower level
  s.add(-6, 4, 0, 0.6, 4.15, 2.5, false);    // wall with two doorways
  s.add(1.4, 4, 0, 3.6, 4.15, 2.5, false);
  s.add(3.6 + second_door, 4, 0, 10, 4.15, 2.5, false);
  s.add(-3.15, -6, 0, -3.0, 4, 0.9, false);    // half wall
  s.add(2.1, -2.4, 0, 2.9, -1.6, 0.6, false);  // box obstacle
  return s;
}

struct ScanRun {
  test::SyntheticScan scan;
  TraversabilityResult result;
  Pose3 T_world_base;
  Eigen::Vector3d world(uint32_t i) const { return T_world_base * result.graph.nodes[i].position; }
};

inline ScanRun runAt(const Scene& scene, double x, double y, double yaw, double roll = 0.0,
                     TraversabilityConfig config = {}) {
  ScanRun run;
  run.T_world_base = poseFromXyzRpy(x, y, 0.0, roll, 0.0, yaw);
  const Pose3 T_world_sensor = run.T_world_base * poseFromXyzRpy(0, 0, kSensorHeight, 0, 0, 0);
  run.scan = castScan(scene, LidarModel::os0_128(), T_world_sensor, run.T_world_base);
  run.result = TraversabilityMapper(config).process(run.scan.cloud);
  return run;
}

}  // namespace tacs::test
