// The map products of a run: the point-cloud map (map.pcd), the OctoMap (map.bt) and the top-down
// picture of the scene graph (topdown.png), built from keyframe clouds and optimised poses.
#pragma once

#include <map>
#include <string>

#include "tacs_graphs/common/keyframe_retention.h"
#include "tacs_graphs/common/types.h"
#include "tacs_graphs/scene_graph/scene_graph.h"

namespace tacs {

struct MapExportConfig {
  double cloud_voxel_m = 0.1;               // voxel size of map.pcd and /tacs/map_points [m]
  double octomap_resolution_m = 0.1;        // leaf size of map.bt [m]
  double octomap_max_range_m = 15.0;        // rays longer than this only mark free space so far [m]
  double octomap_ray_voxel_m = 0.0;         // rays thinned to one per voxel (0: every leaf) [m]
  double topdown_resolution_m = 0.05;       // metres per pixel of topdown.png
  KeyframeRetentionConfig cloud_retention;  // keyframe clouds kept per place for the map

  template <class V>
  void visit(V& v) {
    v("cloud_voxel_m", cloud_voxel_m);
    v("octomap_resolution_m", octomap_resolution_m);
    v("octomap_max_range_m", octomap_max_range_m);
    v("octomap_ray_voxel_m", octomap_ray_voxel_m);
    v("topdown_resolution_m", topdown_resolution_m);
    v("cloud_retention", cloud_retention);
  }
  void validate() const;
};

/// Keyframe clouds (base frame) by keyframe id.
using KeyframeClouds = std::map<uint32_t, PointCloud::ConstPtr>;

class Backend;

/// The keyframe clouds the map products are built from. On long runs a place keeps the clouds of
/// about two passes (map_export.cloud_retention); later keyframes there keep only their poses.
class MapClouds {
 public:
  explicit MapClouds(const KeyframeRetentionConfig& retention) : retention_(retention) {}
  /// Stores a new keyframe's cloud (null: none) and releases a cloud that became redundant,
  /// judged at the backend's current position estimates.
  void add(uint32_t id, PointCloud::ConstPtr cloud, const Backend& backend);
  const KeyframeClouds& clouds() const { return clouds_; }

 private:
  KeyframeClouds clouds_;
  KeyframeRetention retention_;
};

/// All keyframe clouds moved into the map frame with the scene graph's poses, voxel-downsampled.
PointCloud buildMapCloud(const SceneGraph& graph, const KeyframeClouds& clouds, double voxel_m);

/// Builds an OctoMap by ray casting every keyframe cloud (base frame) from its sensor origin,
/// `sensor_in_base` in the base frame, and writes it as a binary .bt file through a temporary
/// file (never half-written). Throws std::runtime_error.
void writeOctomap(const std::string& path, const SceneGraph& graph, const KeyframeClouds& clouds,
                  const MapExportConfig& config,
                  const Eigen::Vector3d& sensor_in_base = Eigen::Vector3d::Zero());

/// Writes a .pcd (binary) through a temporary file. Throws std::runtime_error.
void writePcdAtomically(const std::string& path, const PointCloud& cloud);

}  // namespace tacs
