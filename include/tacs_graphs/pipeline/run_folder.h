// The run folder of docs/DESIGN.md, written from a finished Pipeline: trajectory_tum.txt,
// odometry_tum.txt, scene_graph.json, timing.json, config.json, map.pcd, map.bt and topdown.png.
// Every file is written through a temporary file, so a crash never leaves a half-written one.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "tacs_graphs/pipeline/pipeline.h"

namespace tacs {

struct RunInfo {
  std::string source;        // the bag or world the run read
  double wall_time_s = 0.0;  // wall time of the processing loop
};

/// timing.json: scans, keyframes, wall time, scans per second, per-stage milliseconds
/// (total, mean, max, calls), t_fgo_s, t_ld_s and loop_detection (detections, GICP
/// registrations, loops by path).
nlohmann::json timingJson(const Pipeline& pipeline, const RunInfo& info);

/// Writes the whole run folder (created if needed). Throws std::runtime_error naming the file.
/// Returns the milliseconds each product took: graph (the text files), map.pcd, map.bt,
/// topdown.png.
std::map<std::string, double> writeRunFolder(const std::string& dir, const Pipeline& pipeline,
                                             const RunInfo& info);

/// Draws topdown.png of a scene graph over the map points.
void writeTopdown(const std::string& path, const SceneGraph& graph, const PointCloud& map_points,
                  double resolution_m);

}  // namespace tacs
