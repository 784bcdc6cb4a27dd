// The ground-truth motion of the simulated robot: the waypoint polyline (repeated for `laps`),
// corners rounded by a moving average over `corner_radius_m` of arc length, heading along the
// path, the base on the floor under it, plus a small smooth vibration (roll, pitch, z) as a ground
// robot shows. The speed is `speed_mps` on straights; it drops in turns so the yaw rate stays
// under `max_yaw_rate_dps` (sharp turns become turns in place) and changes by at most
// `max_accel_mps2` (the robot starts and stops at rest); with `max_yaw_accel_dps2` the yaw rate
// too ramps up and down instead of stepping.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tacs_graphs/common/types.h"
#include "tacs_graphs/sim/world.h"

namespace tacs::sim {

/// The world's trajectory started at waypoint `k` instead of the first, so a second session
/// starts elsewhere in the same building. A closed path (last waypoint = first) is driven round
/// from `k` back to `k`; an open path is driven from `k` to its end and back to its first
/// waypoint (every segment is one of the world's, so the path never crosses a wall). Laps and
/// speeds are kept. Throws WorldError when `k` is not a waypoint index.
TrajectorySpec startingAtWaypoint(const TrajectorySpec& spec, int k, const std::string& name);

class RobotPath {
 public:
  /// Throws WorldError when a waypoint or a part of the path is not above any floor.
  RobotPath(const World& world, uint64_t seed, const std::string& name = "world");

  /// Pose of base_link in the world frame at `t` seconds after the start (clamped to the path).
  Pose3 poseAt(double t) const;

  double duration() const { return time_.back(); }  // [s]
  double length() const { return length_; }         // [m], of the smoothed path
  /// The smoothed path, one point every few centimetres (for drawing).
  const std::vector<Eigen::Vector3d>& samples() const { return samples_; }

 private:
  /// samples_, arc_ and length_ from the dense waypoint polyline, its corners rounded.
  void roundCorners(const World& world, const std::vector<Eigen::Vector3d>& dense,
                    const std::string& name);
  void computeHeadings();  // yaw_
  /// time_: the speed profile under the yaw-rate and acceleration limits.
  /// Splits every sample step that turns by more than `max_dyaw` [rad] into equal parts.
  void subdivideTurns(double max_dyaw);
  void computeTiming(const TrajectorySpec& spec);

  std::vector<Eigen::Vector3d> samples_;  // x, y, floor z
  std::vector<double> arc_;               // cumulative arc length at each sample
  std::vector<double> yaw_;               // unwrapped heading at each sample [rad]
  std::vector<double> time_;              // time at which the robot reaches each sample [s]
  double length_ = 0.0;
  double jitter_rad_ = 0.0;
  double jitter_z_ = 0.0;
  double phase_[9] = {};
};

}  // namespace tacs::sim
