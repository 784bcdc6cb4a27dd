// Experiments of tacs_eval: the method configurations compared (config/eval/methods.yaml) and the
// scores of one finished run folder (docs/DESIGN.md "Evaluation").
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tacs_graphs/common/types.h"
#include "tacs_graphs/eval/room_metrics.h"
#include "tacs_graphs/eval/wall_metrics.h"
#include "tacs_graphs/scene_graph/scene_graph.h"

namespace tacs {

/// One method: a name for folders, a label for tables and the configuration it changes.
struct EvalMethod {
  std::string name;
  std::string label;
  nlohmann::json overrides = nlohmann::json::object();  // merged into the base configuration
};

/// Reads `methods: [{name, label, config}]`. Throws ConfigError naming the file and entry.
std::vector<EvalMethod> loadEvalMethods(const std::string& yaml_path);

/// `patch` merged into `base`: objects recursively, every other value replaced.
nlohmann::json mergeJson(nlohmann::json base, const nlohmann::json& patch);

/// The scores of one run folder written by tacs_offline --world.
struct RunScores {
  size_t scans = 0, keyframes = 0, walls = 0, rooms = 0;
  double wall_time_s = 0.0;
  double path_m = 0.0;      // ground-truth path length
  double ate_m = 0.0;       // optimised keyframes, SE(3)-aligned
  double odom_ate_m = 0.0;  // raw odometry of every scan
  double drift_pct = 0.0;   // odometry drift per 10 m
  double t_fgo_s = 0.0, t_ld_s = 0.0;
  size_t loops = 0, correct_loops = 0;
  double pr_loop = 0.0;
  Pose3 T_world_map = Pose3::Identity();  // the alignment of the map onto the world
  SceneGraph graph;                       // as estimated, map frame
  std::vector<RoomRegion> room_regions;   // the rooms' floors in the world frame (by T_world_map)
  RoomMetrics room_metrics;               // against the ground-truth rooms (ground_truth.json)
  WallMetrics wall_metrics;               // the walls against the ground-truth walls
};

/// Reads trajectory_tum.txt, odometry_tum.txt, ground_truth_tum.txt, ground_truth.json,
/// scene_graph.json and timing.json of `dir`. Throws std::runtime_error naming the missing or
/// broken file.
RunScores scoreRunFolder(const std::string& dir);

/// The scene graph moved by T (keyframes, walls, rooms; loops are relative and stay).
SceneGraph transformSceneGraph(const SceneGraph& graph, const Pose3& T);

}  // namespace tacs
