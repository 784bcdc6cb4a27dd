// The run folder of docs/DESIGN.md, written from a finished Pipeline: trajectory_tum.txt,
// odometry_tum.txt, scene_graph.json, timing.json, config.json, map.pcd, map.bt and topdown.png.
// Every file is written through a temporary file, so a crash never leaves a half-written one.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
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

/// The frame and graph a run folder is written in: by default the session's own map frame and
/// graph. A session placed in a prior map (relocalization/prior_session.h) is written in the
/// prior's frame, with the prior's or the merged graph.
struct RunView {
  Pose3 T_out_map = Pose3::Identity();  // moves the trajectories, the graph and the clouds
  std::optional<SceneGraph> graph;      // scene_graph.json and topdown.png (default: the moved
                                        // session graph)
  PointCloud extra_map_points;          // joined into map.pcd (a prior's map), output frame
};

/// Writes the whole run folder (created if needed). Throws std::runtime_error naming the file.
/// Returns the milliseconds each product took: graph (the text files), map.pcd, map.bt,
/// topdown.png.
std::map<std::string, double> writeRunFolder(const std::string& dir, const Pipeline& pipeline,
                                             const RunInfo& info, const RunView& view = {});

/// Draws topdown.png of a scene graph over the map points.
void writeTopdown(const std::string& path, const SceneGraph& graph, const PointCloud& map_points,
                  double resolution_m);

}  // namespace tacs
