// A saved scene graph read back as the prior map of a later session (docs/DESIGN.md "Prior
// maps"): the run folder's scene_graph.json (format "tacs_graphs scene graph", its version) and
// map.pcd (the keyframe clouds in the map frame, voxelised by map_export.cloud_voxel_m). Only
// read: nothing in the folder is ever written.
#pragma once

#include <stdexcept>
#include <string>

#include "tacs_graphs/common/types.h"
#include "tacs_graphs/scene_graph/scene_graph.h"

namespace tacs {

/// A missing or unusable prior; the message names the file and what is wrong with it.
class PriorMapError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct PriorMap {
  std::string dir;
  SceneGraph graph;
  PointCloud points;  // map.pcd: map frame

  /// Reads RUN_DIR/scene_graph.json and RUN_DIR/map.pcd. Throws PriorMapError naming the file:
  /// missing folder or file, invalid JSON, another format or version, a bad field, an unreadable
  /// or empty point cloud, or a graph without a room (nothing to relocalize by).
  static PriorMap load(const std::string& dir);
};

}  // namespace tacs
