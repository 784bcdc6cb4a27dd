// The whole configuration of a run: one section per module, as in config/*.yaml. The nodes read
// it from the ROS parameter server (namespace /tacs by default), the offline tools from the file.
#pragma once

#include <string>
#include <vector>

#include "tacs_graphs/backend/factor_graph.h"
#include "tacs_graphs/backend/map_export.h"
#include "tacs_graphs/common/config.h"
#include "tacs_graphs/common/frames.h"
#include "tacs_graphs/loop_closure/loop_closure_config.h"
#include "tacs_graphs/odometry/lidar_odometry.h"
#include "tacs_graphs/relocalization/room_relocalizer.h"
#include "tacs_graphs/rooms/rooms_config.h"
#include "tacs_graphs/traversability/traversability_config.h"
#include "tacs_graphs/walls/walls_config.h"

namespace tacs {

struct PipelineConfig {
  FramesConfig frames;
  OdometryConfig odometry;
  WallsConfig walls;
  BackendConfig backend;
  TraversabilityConfig traversability;
  MapExportConfig map_export;
  RoomsConfig rooms;
  LoopClosureConfig loop_closure;
  RelocalizationConfig relocalization;  // used with a prior map only

  template <class V>
  void visit(V& v) {
    v("frames", frames);
    v("odometry", odometry);
    v("walls", walls);
    v("backend", backend);
    v("traversability", traversability);
    v("map_export", map_export);
    v("rooms", rooms);
    v("loop_closure", loop_closure);
    v("relocalization", relocalization);
  }
  void validate() const;
};

/// A loaded configuration and the keys in it that no field claimed (likely typos).
struct LoadedPipelineConfig {
  PipelineConfig config;
  std::vector<std::string> unknown_keys;
};

/// Loads and validates a YAML configuration file. Throws ConfigError naming the file and key.
LoadedPipelineConfig loadPipelineConfig(const std::string& yaml_path);

}  // namespace tacs
