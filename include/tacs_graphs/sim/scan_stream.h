// The simulated LiDAR: renders one sweep after another along the robot path, lazily and
// deterministically (same world, options and seed -> identical scans). Used by tacs_sim to write
// bags and by the offline runner to consume a world without a bag.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tacs_graphs/common/types.h"
#include "tacs_graphs/sim/ray_caster.h"
#include "tacs_graphs/sim/robot_path.h"
#include "tacs_graphs/sim/world.h"

namespace tacs::sim {

/// One return in the sensor frame. ring 0 is the lowest beam; time: s since the sweep start.
struct SimPoint {
  float x, y, z, intensity;
  uint16_t ring;
  float time;
};

struct SimScan {
  double stamp = 0.0;  // [s] sweep start; the first scan is at SimOptions::start_stamp
  std::vector<SimPoint> points;
  Pose3 T_world_base = Pose3::Identity();  // ground truth at `stamp`
};

struct SimOptions {
  std::optional<uint64_t> seed;           // overrides the world's sensor.seed when set
  double duration_s = 0.0;                // 0: the whole trajectory
  double start_stamp = 1000.0;            // [s] stamp of the first scan
  std::optional<bool> motion_distortion;  // overrides sensor.motion_distortion when set
  int start_waypoint = 0;  // the trajectory starts at this waypoint (startingAtWaypoint)
};

class ScanStream {
 public:
  /// Throws WorldError when the trajectory leaves the floors.
  ScanStream(const World& world, const SimOptions& options);

  /// Renders the next sweep; false after the last one.
  bool next(SimScan* scan);
  /// Renders sweep `index` (< scanCount()) without moving the stream.
  void render(size_t index, SimScan* scan) const;

  Pose3 baseToSensor() const;      // T_base_sensor: the sensor sits mount_height_m above base
  Trajectory groundTruth() const;  // base pose at every scan stamp, world frame
  size_t scanCount() const { return count_; }
  const SensorSpec& sensor() const { return sensor_; }
  const RobotPath& path() const { return path_; }
  uint64_t seed() const { return seed_; }

 private:
  /// The returns of firings [begin, end) of sweep `index`, in firing order.
  void renderColumns(size_t index, size_t begin, size_t end, RayCaster::Marks* marks,
                     std::vector<SimPoint>* out) const;

  World world_;
  SimOptions options_;
  SensorSpec sensor_;
  uint64_t seed_;
  RobotPath path_;
  std::unique_ptr<RayCaster> caster_;
  size_t count_ = 0;
  size_t next_ = 0;
  std::vector<double> cos_el_, sin_el_, cos_az_, sin_az_;
};

/// XYZI cloud in the sensor frame (for the core pipeline), stamped in microseconds as PCL does.
PointCloud toPointCloud(const SimScan& scan);

/// The points' times as a driver would write them in `field` (SensorSpec::time_field): "time"
/// float32 seconds, "t" whole nanoseconds, both since the sweep start (the scan's stamp).
std::vector<double> rawPointTimes(const SimScan& scan, const std::string& field);

}  // namespace tacs::sim
