// sensor_msgs/PointCloud2 <-> core PointCloud, checked field by field.
//
// Real drivers differ: Velodyne publishes float32 x y z intensity ring time, Ouster adds t/range/
// reflectivity and pads points, some tools write float64 coordinates. The conversion reads x y z
// (float32 or float64) and intensity when present (any numeric type), and reports instead of
// throwing when the message cannot be a point cloud, so a node can log once and carry on.
#pragma once

#include <sensor_msgs/PointCloud2.h>

#include <string>

#include "tacs_graphs/common/types.h"

namespace tacs {

struct CloudConversionResult {
  bool ok = false;
  std::string error;      // why the message was rejected (ok == false)
  size_t points_in = 0;   // width * height of the message
  size_t non_finite = 0;  // points dropped for NaN/inf coordinates
};

/// Converts `msg` into `cloud` (frame and stamp are left to the caller). Rejects messages without
/// x/y/z fields, with inconsistent sizes (data shorter than row_step * height, point_step smaller
/// than the fields) or with unsupported field types. Non-finite points are dropped and counted.
CloudConversionResult fromRosCloud(const sensor_msgs::PointCloud2& msg, PointCloud* cloud);

/// Converts a core cloud to a PointCloud2 with float32 fields x y z intensity.
sensor_msgs::PointCloud2 toRosCloud(const PointCloud& cloud, const std::string& frame_id,
                                    double stamp);

}  // namespace tacs
