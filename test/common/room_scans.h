// The real PCL tutorial room scans (data set pcl_room_scans, see README "Test data"): one
// furnished room, sensor frame, floor about 1.24 m below the sensor.
#pragma once

#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>

#include <string>

#include "common/real_data.h"
#include "tacs_graphs/common/types.h"

namespace tacs::test {

constexpr char kRoomScansSet[] = "pcl_room_scans";

/// `dir`/`name` (room_scan1.pcd or room_scan2.pcd); a test failure (and an empty cloud) when it
/// cannot be read.
inline PointCloud loadRoomScan(const std::string& dir, const std::string& name) {
  pcl::PointCloud<pcl::PointXYZ> xyz;
  if (pcl::io::loadPCDFile(dir + name, xyz) != 0) {
    ADD_FAILURE() << "cannot read " << dir + name;
    return {};
  }
  PointCloud cloud;
  pcl::copyPointCloud(xyz, cloud);
  return cloud;
}

}  // namespace tacs::test
