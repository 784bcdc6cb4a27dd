// Voxel free-space baseline in the style of S-Graphs+ (reference/s_graphs.md, Sec. 2; paper
// Sec. II-B): what the paper compares TACS against.
//
// Keyframe clouds are integrated into a 2D occupancy slice of the space at robot height: each ray
// from the sensor to a return is clipped to the height band [band_min, band_max] above the robot's
// floor and max_ray_length; the cells it crosses in the band are observed free, the cell of a
// return inside the band is hit. A cell with min_hits returns is occupied (occupancy wins over
// free, as in an ESDF built from surfaces). Clusters: free cells farther than doorway_clearance
// (0.8 m, hard-coded in S-Graphs+) from any occupied cell are split into 4-connected components;
// components below min_cluster_area are dropped; the free cells that were cut are given to the
// nearest component (breadth-first), as S-Graphs+ re-attaches removed skeleton vertices.
// The slice does not know whether a floor exists under free space: space over a drop-off is free,
// which is the under-segmentation of voxel methods the paper describes.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "tacs_graphs/common/types.h"
#include "tacs_graphs/rooms/rooms_config.h"

namespace tacs {

class VoxelFreeSpace {
 public:
  struct Cluster {
    std::vector<Eigen::Vector3d> points;  // map-frame cell centres (z: robot floor height)
    std::vector<uint32_t> keyframe_ids;   // keyframes whose position lies in the cluster
  };

  /// Validates the config (throws ConfigError).
  explicit VoxelFreeSpace(const VoxelFreeSpaceConfig& config);

  /// Integrates one keyframe cloud given in the base frame (base_link on the floor) at pose
  /// T_map_base; rays start at `sensor_in_base`.
  void integrate(uint32_t keyframe_id, const PointCloud& cloud_in_base, const Pose3& T_map_base,
                 const Eigen::Vector3d& sensor_in_base);

  /// Current free-space clusters, largest first.
  std::vector<Cluster> clusters() const;

  size_t knownCells() const { return cells_.size(); }
  void clear();

 private:
  struct Cell {
    uint16_t hits = 0;
    uint16_t free = 0;
    float floor_z = 0.0f;
  };
  int64_t key(int64_t ix, int64_t iy) const { return (ix << 32) ^ (iy & 0xffffffff); }
  int64_t cellIndex(double v) const;

  VoxelFreeSpaceConfig config_;
  std::unordered_map<int64_t, Cell> cells_;
  std::vector<std::pair<uint32_t, Eigen::Vector3d>> keyframes_;
};

}  // namespace tacs
