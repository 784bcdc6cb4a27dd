#include "tacs_graphs/backend/map_export.h"

#include <pcl/common/transforms.h>
#include <pcl/io/pcd_io.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "tacs_graphs/backend/backend.h"
#include "tacs_graphs/common/config.h"
#include "tacs_graphs/odometry/preprocess.h"

namespace tacs {

void MapExportConfig::validate() const {
  requireConfig(cloud_voxel_m > 0, "map_export.cloud_voxel_m", "must be > 0");
  requireConfig(octomap_resolution_m > 0, "map_export.octomap_resolution_m", "must be > 0");
  requireConfig(octomap_max_range_m > 0, "map_export.octomap_max_range_m", "must be > 0");
  requireConfig(octomap_ray_voxel_m >= 0, "map_export.octomap_ray_voxel_m",
                "must be >= 0 (0: a ray to every point)");
  requireConfig(topdown_resolution_m > 0, "map_export.topdown_resolution_m", "must be > 0");
  cloud_retention.validate("map_export.cloud_retention.");
}

void MapClouds::add(uint32_t id, PointCloud::ConstPtr cloud, const Backend& backend) {
  if (cloud) clouds_[id] = std::move(cloud);
  const auto position_of = [&backend](uint32_t k) { return backend.keyframePosition(k); };
  if (const auto released = retention_.add(id, position_of)) clouds_.erase(*released);
}

PointCloud buildMapCloud(const SceneGraph& graph, const KeyframeClouds& clouds, double voxel_m) {
  PointCloud all;
  for (const auto& [id, cloud] : clouds) {
    const auto it = graph.keyframes.find(id);
    if (it == graph.keyframes.end() || !cloud) continue;
    PointCloud moved;
    pcl::transformPointCloud(*cloud, moved, it->second.pose().matrix().cast<float>());
    all += moved;
  }
  return voxelDownsample(all, voxel_m);
}

void writePcdAtomically(const std::string& path, const PointCloud& cloud) {
  const std::string tmp = path + ".tmp.pcd";
  if (cloud.empty()) {
    // PCL refuses to write an empty cloud; an empty map is still a valid, readable result.
    std::ofstream(tmp)
        << "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\n"
           "TYPE F F F F\nCOUNT 1 1 1 1\nWIDTH 0\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\n"
           "POINTS 0\nDATA ascii\n";
  } else if (pcl::io::savePCDFileBinary(tmp, cloud) != 0) {
    throw std::runtime_error(path + ": cannot write point cloud");
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace tacs
