// Writes simulated sweeps into a bag laid out like the recorded sequences: the cloud
// (sensor_msgs/PointCloud2 with fields x y z intensity ring time, as the velodyne driver
// publishes), /tf_static base_link -> sensor and ground truth nav_msgs/Odometry in frame world.
#pragma once

#include <rosbag/bag.h>
#include <sensor_msgs/PointCloud2.h>

#include <memory>
#include <string>

#include "tacs_graphs/sim/scan_stream.h"

namespace tacs {

/// The cloud of one sweep: 22-byte points (float32 x y z intensity, uint16 ring, float32 time).
/// x y z intensity ring and the per-point time as the driver of `time_field` writes it:
/// "time" float32 s (Velodyne) or "t" uint32 ns (Ouster), since the sweep start.
/// An empty `time_field` writes x y z intensity ring only.
sensor_msgs::PointCloud2 simScanToPointCloud2(const sim::SimScan& scan, const std::string& frame_id,
                                              const std::string& time_field = "time");

class SimBagWriter {
 public:
  struct Options {
    std::string cloud_topic = "/velodyne_points";
    std::string odom_topic = "/ground_truth/odom";
    std::string sensor_frame = "velodyne";
    std::string base_frame = "base_link";
    std::string world_frame = "world";
    std::string time_field = "time";  // SensorSpec::time_field
    // Per-point times are written only for sweeps rendered with motion distortion: an
    // undistorted sweep was rendered from one pose, and its firing times would mislead deskew.
    bool point_times = true;
  };

  /// Opens (truncates) `path`. Throws rosbag::BagException on failure.
  SimBagWriter(const std::string& path, const Pose3& T_base_sensor, const Options& options);
  ~SimBagWriter();

  /// Appends one sweep and its ground-truth odometry (twist from the previous sweep, in the base
  /// frame). The first call also writes the latched /tf_static.
  void write(const sim::SimScan& scan);
  void close();

 private:
  rosbag::Bag bag_;
  Pose3 T_base_sensor_;
  Options options_;
  bool first_ = true;
  sim::SimScan previous_;
};

}  // namespace tacs
