#include "tacs_graphs/pipeline/run_folder.h"

#include <algorithm>
#include <cmath>

#include "tacs_graphs/common/file_io.h"
#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/common/trajectory_io.h"
#include "tacs_graphs/odometry/preprocess.h"
#include "tacs_graphs/viz/scene_graph_drawing.h"

namespace tacs {

nlohmann::json timingJson(const Pipeline& pipeline, const RunInfo& info) {
  const PipelineStats& stats = pipeline.stats();
  nlohmann::json j;
  j["source"] = info.source;
  j["scans"] = stats.scans;
  j["rejected_scans"] = stats.rejected_scans;
  j["deskewed_scans"] = stats.deskewed_scans;
  j["odometry_recoveries"] = stats.odometry_recoveries;
  j["keyframes"] = stats.keyframes;
  j["wall_observations"] = stats.wall_observations;
  j["wall_time_s"] = info.wall_time_s;
  j["scans_per_s"] = info.wall_time_s > 0 ? stats.scans / info.wall_time_s : 0.0;
  nlohmann::json stages = nlohmann::json::object();
  for (const auto& [name, e] : pipeline.stageTimes().entries()) {
    stages[name] = {{"total_ms", e.total_ms},
                    {"mean_ms", e.calls ? e.total_ms / e.calls : 0.0},
                    {"max_ms", e.max_ms},
                    {"calls", e.calls}};
  }
  j["stages_ms"] = stages;
  j["t_fgo_s"] = pipeline.fgoSeconds();
  j["t_fgo_cpu_s"] = pipeline.fgoCpuSeconds();
  j["t_ld_s"] = pipeline.ldSeconds();
  const LoopDetectorStats& lcd = pipeline.loopDetector().stats();
  j["loop_detection"] = {{"detections", lcd.detections},
                         {"registrations", lcd.registrations},
                         {"coarse_loops", lcd.coarse_loops},
                         {"fine_loops", lcd.fine_loops},
                         {"distance_loops", lcd.distance_loops}};
  j["optimizations"] = pipeline.backend().optimizations();
  return j;
}

void writeTopdown(const std::string& path, const SceneGraph& graph, const PointCloud& map_points,
                  double resolution_m) {
  Eigen::Vector2d lo, hi;
  viz::sceneGraphBounds(graph, nullptr, 2.0, &lo, &hi);
  // A picture of at most about 4000 px a side, whatever the extent of the run.
  const double extent = std::max((hi - lo).maxCoeff(), 1.0);
  const double resolution = std::max(resolution_m, extent / 4000.0);
  viz::Canvas canvas(lo, hi, resolution);
  viz::drawSceneGraph(graph, &map_points, &canvas);
  canvas.savePng(path);
}

namespace {

Trajectory moved(const Trajectory& trajectory, const Pose3& T) {
  Trajectory out = trajectory;
  if (T.matrix().isIdentity(0.0)) return out;
  for (StampedPose& p : out) p.pose = T * p.pose;
  return out;
}

}  // namespace

std::map<std::string, double> writeRunFolder(const std::string& dir, const Pipeline& pipeline,
                                             const RunInfo& info, const RunView& view) {
  ensureDirectory(dir);
  std::map<std::string, double> ms;
  Stopwatch watch;
  const auto lap = [&](const char* name) {
    ms[name] = watch.elapsedMs();
    watch = Stopwatch();
  };
  // Moved only when there is somewhere to move it: a round trip through the rotation matrix
  // would change the last bits of every quaternion of an ordinary run.
  const bool moves = !view.T_out_map.matrix().isIdentity(0.0);
  const SceneGraph session =
      moves ? pipeline.sceneGraph().transformed(view.T_out_map) : pipeline.sceneGraph();
  const SceneGraph& graph = view.graph ? *view.graph : session;
  const MapExportConfig& map_config = pipeline.config().map_export;
  writeTum(dir + "/trajectory_tum.txt", moved(pipeline.keyframeTrajectory(), view.T_out_map));
  writeTum(dir + "/odometry_tum.txt", moved(pipeline.odometryTrajectory(), view.T_out_map));
  graph.save(dir + "/scene_graph.json");
  writeFileAtomically(dir + "/timing.json", timingJson(pipeline, info).dump(2) + "\n");
  writeFileAtomically(dir + "/config.json", configToJson(pipeline.config()).dump(2) + "\n");
  lap("graph");
  PointCloud map = buildMapCloud(session, pipeline.keyframeClouds(), map_config.cloud_voxel_m);
  if (!view.extra_map_points.empty()) {
    map = voxelDownsample(map + view.extra_map_points, map_config.cloud_voxel_m);
  }
  writePcdAtomically(dir + "/map.pcd", map);
  lap("map.pcd");
  writeOctomap(dir + "/map.bt", session, pipeline.keyframeClouds(), map_config,
               pipeline.sensorInBase());
  lap("map.bt");
  writeTopdown(dir + "/topdown.png", graph, map, map_config.topdown_resolution_m);
  lap("topdown.png");
  return ms;
}

}  // namespace tacs
