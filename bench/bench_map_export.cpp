// bench_map_export: time of writing map.bt (writeOctomap) on the keyframes of a simulated world,
// without the rest of the pipeline, so that its cost is measured apart from the machine's load
// during a run. Keyframe clouds are the world's sweeps every --every scans (tacs_offline makes a
// keyframe every 0.5 m: about every 5th scan at 1 m/s) on the keyframe cloud's 0.1 m grid, at
// their ground-truth poses. Prints one table row per world: keyframes, their points, the minimum
// and mean time over --reps writes, and the file's size.
//   bench_map_export [--world NAME|FILE ...] [--every N] [--reps N] [--config YAML]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "bench_worlds_common.h"
#include "tacs_graphs/backend/map_export.h"
#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/odometry/preprocess.h"
#include "tacs_graphs/scene_graph/scene_graph.h"

namespace {

const char* kUsage =
    "usage: bench_map_export [--world NAME|FILE ...] [--every N] [--reps N] [--config YAML]\n";

// Pulls --every N and --reps N out of argv; the rest goes to parseWorldsArgs.
std::vector<char*> takeCounts(int argc, char** argv, int* every, int* reps) {
  std::vector<char*> rest = {argv[0]};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--every" || a == "--reps") && i + 1 < argc) {
      (a == "--every" ? *every : *reps) = std::max(1, std::atoi(argv[++i]));
    } else {
      rest.push_back(argv[i]);
    }
  }
  return rest;
}

}  // namespace

int main(int argc, char** argv) {
  int every = 5, reps = 3;
  std::vector<char*> rest = takeCounts(argc, argv, &every, &reps);
  tacs::bench::WorldsArgs args;
  if (!tacs::bench::parseWorldsArgs(static_cast<int>(rest.size()), rest.data(), kUsage, &args)) {
    return 2;
  }
  const std::string out = (std::filesystem::temp_directory_path() / "bench_map_export.bt").string();
  std::printf(
      "| world | keyframes | points | map.bt min s | mean s | MB |\n|---|---|---|---|---|---|\n");
  for (const std::string& path : tacs::bench::worldPaths(&args)) {
    const tacs::sim::World world = tacs::sim::loadWorld(path);
    const tacs::sim::ScanStream stream(world, tacs::sim::SimOptions{});
    const tacs::Pose3 T_base_sensor = stream.baseToSensor();
    tacs::SceneGraph graph;
    tacs::KeyframeClouds clouds;
    size_t points = 0;
    tacs::sim::SimScan scan;
    for (size_t i = 0; i < stream.scanCount(); i += static_cast<size_t>(every)) {
      stream.render(i, &scan);
      const tacs::Pose3 T_world_level = tacs::bench::levelledPose(scan.T_world_base);
      auto cloud = std::make_shared<tacs::PointCloud>(tacs::voxelDownsample(
          tacs::bench::levelledCloud(scan, T_base_sensor, T_world_level), 0.1));
      const uint32_t id = static_cast<uint32_t>(graph.keyframes.size());
      tacs::KeyframeNode& node = graph.keyframes[id];
      node.id = id;
      node.stamp = scan.stamp;
      node.setPose(T_world_level);
      points += cloud->size();
      clouds[id] = cloud;
    }
    double min_s = 1e30, sum_s = 0.0;
    for (int r = 0; r < reps; ++r) {
      tacs::Stopwatch watch;
      tacs::writeOctomap(out, graph, clouds, args.config.map_export, T_base_sensor.translation());
      const double s = watch.elapsedMs() / 1000.0;
      min_s = std::min(min_s, s);
      sum_s += s;
    }
    std::printf("| %s | %zu | %zu | %.2f | %.2f | %.1f |\n", world.name.c_str(), clouds.size(),
                points, min_s, sum_s / reps, std::filesystem::file_size(out) / 1e6);
    std::fflush(stdout);
  }
  std::filesystem::remove(out);
  return 0;
}
