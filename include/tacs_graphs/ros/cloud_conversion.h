// sensor_msgs/PointCloud2 <-> core PointCloud, checked field by field.
//
// Real drivers differ: Velodyne publishes float32 x y z intensity ring time, Ouster adds t/range/
// reflectivity and pads points, some tools write float64 coordinates. The conversion reads x y z
// (float32 or float64) and intensity when present (any numeric type), and reports instead of
// throwing when the message cannot be a point cloud, so a node can log once and carry on.
#pragma once

#include <sensor_msgs/PointCloud2.h>

#include <string>
#include <vector>

#include "tacs_graphs/common/types.h"
#include "tacs_graphs/odometry/point_times.h"

namespace tacs {

struct CloudConversionResult {
  bool ok = false;
  std::string error;       // why the message was rejected (ok == false)
  size_t points_in = 0;    // width * height of the message
  size_t non_finite = 0;   // points dropped for NaN/inf coordinates
  std::string time_field;  // the per-point time field read (empty: none asked for or present)
};

/// Which field to read per-point times from: "none", "auto" (the first of
/// autoTimeFieldNames() present in the message) or a field name.
struct TimeFieldRequest {
  std::string field = "none";
  std::vector<double>* raw = nullptr;  // receives one value per kept point, in the field's unit
};

/// Converts `msg` into `cloud` (frame and stamp are left to the caller). Rejects messages without
/// x/y/z fields, with inconsistent sizes (data shorter than row_step * height, point_step smaller
/// than the fields) or with unsupported field types. Non-finite points are dropped and counted.
/// With `times`, the values of the requested time field are read too, aligned with the kept
/// points (an absent field leaves times->raw empty and time_field empty).
CloudConversionResult fromRosCloud(const sensor_msgs::PointCloud2& msg, PointCloud* cloud,
                                   const TimeFieldRequest& times = TimeFieldRequest());

/// A scan with its per-point times resolved (odometry/point_times.h).
struct TimedScan {
  PointCloud cloud;
  CloudConversionResult conversion;
  PointTimes times;  // times.ok == false: no usable times (times.reason/message say why)
};

/// fromRosCloud plus resolvePointTimes for `config` against the header stamp `stamp`.
TimedScan fromRosCloudWithTimes(const sensor_msgs::PointCloud2& msg, double stamp,
                                const PointTimeConfig& config);

/// Converts a core cloud to a PointCloud2 with float32 fields x y z intensity.
sensor_msgs::PointCloud2 toRosCloud(const PointCloud& cloud, const std::string& frame_id,
                                    double stamp);

}  // namespace tacs
