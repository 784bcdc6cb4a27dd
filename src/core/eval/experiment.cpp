#include "tacs_graphs/eval/experiment.h"

#include <fstream>

#include "tacs_graphs/common/config.h"
#include "tacs_graphs/common/trajectory_io.h"
#include "tacs_graphs/eval/loop_metrics.h"
#include "tacs_graphs/eval/trajectory_metrics.h"
#include "tacs_graphs/sim/ground_truth.h"

namespace tacs {

std::vector<EvalMethod> loadEvalMethods(const std::string& yaml_path) {
  const nlohmann::json j = loadYamlAsJson(yaml_path);
  if (!j.is_object() || !j.contains("methods") || !j["methods"].is_array()) {
    throw ConfigError(yaml_path + ": methods: expected a list of {name, label, config}");
  }
  std::vector<EvalMethod> methods;
  for (size_t i = 0; i < j["methods"].size(); ++i) {
    const nlohmann::json& m = j["methods"][i];
    const std::string where = yaml_path + ": methods[" + std::to_string(i) + "]";
    if (!m.is_object() || !m.contains("name") || !m["name"].is_string()) {
      throw ConfigError(where + ".name: expected a string");
    }
    EvalMethod method;
    method.name = m["name"].get<std::string>();
    method.label = m.value("label", method.name);
    if (m.contains("config")) {
      if (!m["config"].is_object() && !m["config"].is_null()) {
        throw ConfigError(where + ".config: expected a mapping");
      }
      if (m["config"].is_object()) method.overrides = m["config"];
    }
    methods.push_back(method);
  }
  return methods;
}

nlohmann::json mergeJson(nlohmann::json base, const nlohmann::json& patch) {
  if (!base.is_object() || !patch.is_object()) return patch;
  for (const auto& [key, value] : patch.items()) {
    base[key] = base.contains(key) ? mergeJson(base[key], value) : value;
  }
  return base;
}

namespace {
nlohmann::json readJson(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open file");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}
}  // namespace

RunScores scoreRunFolder(const std::string& dir) {
  RunScores s;
  const nlohmann::json timing = readJson(dir + "/timing.json");
  s.scans = timing.value("scans", size_t{0});
  s.keyframes = timing.value("keyframes", size_t{0});
  s.wall_time_s = timing.value("wall_time_s", 0.0);
  s.t_fgo_s = timing.value("t_fgo_s", 0.0);
  s.t_ld_s = timing.value("t_ld_s", 0.0);
  s.graph = SceneGraph::load(dir + "/scene_graph.json");
  s.walls = s.graph.wallCount();
  s.rooms = s.graph.rooms.size();
  const Trajectory gt = readTum(dir + "/ground_truth_tum.txt");
  const Trajectory keyframes = readTum(dir + "/trajectory_tum.txt");
  const Trajectory odometry = readTum(dir + "/odometry_tum.txt");
  s.path_m = pathLength(gt);
  const AteResult ate = computeAte(keyframes, gt);
  s.ate_m = ate.rmse;
  s.T_world_map = ate.T_gt_estimate;
  s.odom_ate_m = computeAte(odometry, gt).rmse;
  s.drift_pct = computeDrift(odometry, gt).percent;
  const LoopAccuracy loops = evaluateLoops(s.graph, gt);
  s.loops = loops.loops;
  s.correct_loops = loops.correct;
  s.pr_loop = loops.precision();
  // Rooms are scored in the world frame: the map frame starts at the robot's first pose.
  const SceneGraph in_world = transformSceneGraph(s.graph, s.T_world_map);
  s.room_regions = floorRegions(in_world);
  const sim::GroundTruth truth = sim::readGroundTruth(dir + "/ground_truth.json");
  s.room_metrics = evaluateRooms(s.room_regions, truth.rooms);
  s.wall_metrics = evaluateWalls(in_world, truth.walls);
  return s;
}

SceneGraph transformSceneGraph(const SceneGraph& graph, const Pose3& T) {
  SceneGraph out = graph;
  const Eigen::Matrix2d R = T.linear().topLeftCorner<2, 2>();
  const Eigen::Vector2d t = T.translation().head<2>();
  for (auto& [id, kf] : out.keyframes) kf.setPose(T * kf.pose());
  for (auto& [id, w] : out.walls) {
    // n.p + d = 0 in the map frame -> (R n).q + d - (R n).t = 0 for q = T p.
    w.normal = T.linear() * w.normal;
    w.d -= w.normal.dot(T.translation());
    for (auto& e : w.endpoints) e = R * e + t;
  }
  for (auto& [id, r] : out.rooms) {
    r.center = T * r.center;
    for (auto& p : r.free_space) p = R * p + t;
  }
  return out;
}

}  // namespace tacs
