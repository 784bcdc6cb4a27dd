// The real PCL tutorial room scans of the shared data folder (see its PROVENANCE.md): one
// furnished room, sensor frame, floor about 1.24 m below the sensor.
#pragma once

#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>

#include <filesystem>
#include <string>

#include "common/test_paths.h"
#include "tacs_graphs/common/types.h"

namespace tacs::test {

/// room_scan1.pcd or room_scan2.pcd; a test failure (and an empty cloud) when it cannot be read.
inline PointCloud loadRoomScan(const std::string& name) {
  const std::string path = sharedDataDir() + "/pcl_room_scans/" + name;
  pcl::PointCloud<pcl::PointXYZ> xyz;
  if (!std::filesystem::exists(path) || pcl::io::loadPCDFile(path, xyz) != 0) {
    ADD_FAILURE() << "cannot read " << path;
    return {};
  }
  PointCloud cloud;
  pcl::copyPointCloud(xyz, cloud);
  return cloud;
}

}  // namespace tacs::test
