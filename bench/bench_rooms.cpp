// bench_rooms: room segmentation on the simulated worlds with ground-truth poses, TACS against
// the voxel (S-Graphs+ style) baseline, scored against the worlds' ground-truth rooms.
//
//   bench_rooms [--worlds DIR] [--world NAME|FILE]... [--keyframe-distance M] [--config YAML]
//               [--trials K] [--verbose]
//
// Per world: the simulator renders a scan at every keyframe (every 0.5 m of ground-truth path);
// the scan goes to the gravity-aligned base frame; TraversabilityMapper + TraversableMap and
// WallExtractor + WallMap (duplicates folded at every keyframe) feed one RoomSegmenter per
// method. Printed per world and method: N_room, precision, recall, F1, mean Dice over the
// ground-truth rooms (eval/room_metrics.h), over- and under-segmentation counts, and the mean /
// max time of RoomSegmenter::processKeyframe per keyframe. open_lobby also reports rooms whose
// free space crosses the half wall (x = 12, y < 10) or lies over the railed drop-off. With
// --trials K each world runs with noise seeds 1..K and a consistency table (N_room, sigma_room,
// DCS between trials, paper Table I) follows.
#include <pcl/common/transforms.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_common.h"
#include "bench_worlds_common.h"
#include "tacs_graphs/eval/room_metrics.h"
#include "tacs_graphs/pipeline/pipeline_config.h"
#include "tacs_graphs/rooms/room_segmenter.h"
#include "tacs_graphs/sim/ground_truth.h"
#include "tacs_graphs/sim/scan_stream.h"
#include "tacs_graphs/traversability/traversability_mapper.h"
#include "tacs_graphs/walls/wall_extractor.h"

namespace {

namespace fs = std::filesystem;
using tacs::Pose3;

struct Args {
  std::string worlds_dir;
  std::vector<std::string> worlds;
  double keyframe_distance = 0.5;
  bool verbose = false;
  int trials = 1;  // noise seeds 1..trials; with more than one, N_room, sigma_room and DCS
  tacs::PipelineConfig config;  // --config FILE, else the defaults
};

struct MethodRun {
  tacs::RoomMethod method = tacs::RoomMethod::kTacs;
  std::vector<tacs::RoomNode> rooms;
  std::vector<double> ms;
};

// Over-segmentation: ground-truth rooms covered by two or more estimated rooms (each with most of
// its area inside). Under-segmentation: estimated rooms with >= 20 % of their area in each of two
// or more ground-truth rooms.
void segmentationErrors(const std::vector<tacs::RoomNode>& est,
                        const std::vector<tacs::sim::Room>& gt, int* over, int* under) {
  const tacs::RoomMetricsConfig mc;
  std::vector<tacs::CellSet> g;
  for (const auto& r : gt) g.push_back(tacs::rasterizePolygon(r.polygon, mc.cell));
  std::vector<int> owners(gt.size(), 0);
  *over = *under = 0;
  for (const auto& r : est) {
    const tacs::CellSet e = tacs::rasterizePoints(r.free_space, mc.cell, mc.point_radius);
    int spanned = 0;
    for (size_t k = 0; k < g.size(); ++k) {
      size_t in = 0;
      for (int64_t c : e) in += g[k].count(c);
      const double share = e.empty() ? 0.0 : static_cast<double>(in) / e.size();
      if (share >= 0.5) ++owners[k];
      if (share >= 0.2) ++spanned;
    }
    if (spanned >= 2) ++*under;
  }
  for (int n : owners) *over += n >= 2;
}

// open_lobby: rooms with >= 5 % of their free space on each side of the half wall (x = 12,
// y < 10), and rooms with free space over the drop-off [4, 10] x [12, 18].
void lobbyChecks(const std::vector<tacs::RoomNode>& rooms, int* across_half_wall,
                 int* over_drop_off) {
  *across_half_wall = *over_drop_off = 0;
  for (const auto& r : rooms) {
    size_t west = 0, east = 0, void_points = 0;
    for (const auto& p : r.free_space) {
      if (p.y() < 10.0 && p.x() < 11.9) ++west;
      if (p.y() < 10.0 && p.x() > 12.1) ++east;
      if (p.x() > 4.2 && p.x() < 9.8 && p.y() > 12.2 && p.y() < 17.8) ++void_points;
    }
    const double n = std::max<size_t>(1, r.free_space.size());
    if (west / n >= 0.05 && east / n >= 0.05) ++*across_half_wall;
    if (void_points > 0) ++*over_drop_off;
  }
}

// One run of both methods on a world with the sensor noise seed `seed`; prints a row per method
// and returns the rooms of each method (tacs, voxel).
std::vector<std::vector<tacs::RoomNode>> runWorld(const std::string& path, const Args& args,
                                                  uint64_t seed) {
  const tacs::sim::World world = tacs::sim::loadWorld(path);
  tacs::sim::SimOptions options;
  options.seed = seed;
  tacs::sim::ScanStream stream(world, options);
  const tacs::Trajectory gt = stream.groundTruth();
  const Pose3 T_base_sensor = stream.baseToSensor();

  const tacs::TraversabilityConfig& trav_config = args.config.traversability;
  const tacs::TraversabilityMapper mapper(trav_config);
  tacs::TraversableMap trav_map(trav_config);
  const tacs::WallExtractor extractor{args.config.walls.extraction};
  tacs::WallMap walls(args.config.walls.association);
  std::vector<MethodRun> runs(2);
  runs[0].method = tacs::RoomMethod::kTacs;
  runs[1].method = tacs::RoomMethod::kVoxel;
  std::vector<tacs::RoomSegmenter> segmenters;
  for (const auto& run : runs) {
    tacs::RoomsConfig config = args.config.rooms;
    config.method = run.method;
    // The sensor sits above base_link; the scans are turned into the levelled base frame.
    segmenters.emplace_back(config, args.config.walls.axes,
                            tacs::poseFromXyzRpy(0, 0, T_base_sensor.translation().z(), 0, 0, 0));
  }

  uint32_t keyframes = 0;
  Eigen::Vector3d last(1e9, 1e9, 1e9);
  tacs::sim::SimScan scan;
  for (size_t i = 0; i < gt.size(); ++i) {
    const Pose3& T_world_base = gt[i].pose;
    if ((T_world_base.translation() - last).norm() < args.keyframe_distance) continue;
    last = T_world_base.translation();
    // Levelled base frame: the ground-truth yaw and position, roll and pitch taken out.
    const Eigen::Vector3d fwd = T_world_base.linear().col(0);
    const Pose3 T_map_level =
        tacs::poseFromXyzRpy(T_world_base.translation().x(), T_world_base.translation().y(),
                             T_world_base.translation().z(), 0, 0, std::atan2(fwd.y(), fwd.x()));
    stream.render(i, &scan);
    tacs::PointCloud cloud;
    pcl::transformPointCloud(
        tacs::sim::toPointCloud(scan), cloud,
        (T_map_level.inverse() * T_world_base * T_base_sensor).matrix().cast<float>());
    const uint32_t id = keyframes++;
    trav_map.insert(mapper.process(cloud).graph, T_map_level, id);
    const Eigen::Vector3d sensor =
        T_map_level.inverse() * T_world_base * T_base_sensor.translation();
    walls.associate(extractor.extract(cloud, sensor).walls, T_map_level);
    walls.mergeDuplicates();
    for (size_t m = 0; m < runs.size(); ++m) {
      const auto r = segmenters[m].processKeyframe(id, T_map_level, trav_map, walls, &cloud);
      runs[m].ms.push_back(r.time_ms);
    }
  }
  const tacs::sim::GroundTruth truth = tacs::sim::groundTruthOf(world);
  for (size_t m = 0; m < runs.size(); ++m) {
    const auto r = segmenters[m].finish(trav_map, walls);
    runs[m].ms.push_back(r.time_ms);
    for (const auto& [id, room] : segmenters[m].rooms()) runs[m].rooms.push_back(room.toNode());
    const tacs::RoomMetrics metrics =
        tacs::evaluateRooms(tacs::freeSpaceRegions(runs[m].rooms), truth.rooms);
    int over = 0, under = 0;
    segmentationErrors(runs[m].rooms, truth.rooms, &over, &under);
    double mean = 0.0, max = 0.0;
    for (double t : runs[m].ms) mean += t, max = std::max(max, t);
    mean /= runs[m].ms.size();
    std::printf(
        "| %-17s | %-5s | %4u | %2zu / %2zu | %4.2f | %4.2f | %4.2f | %4.2f | %4d | %5d | %6.2f | "
        "%6.1f |\n",
        world.name.c_str(), tacs::enumName(runs[m].method), keyframes, metrics.estimated,
        metrics.ground_truth, metrics.precision, metrics.recall, metrics.f1, metrics.mean_dice,
        over, under, mean, max);
    if (world.name == "open_lobby") {
      int across = 0, drop = 0;
      lobbyChecks(runs[m].rooms, &across, &drop);
      std::printf(
          "|   open_lobby check | %-5s | rooms across the half wall: %d, over the drop-off: %d |\n",
          tacs::enumName(runs[m].method), across, drop);
    }
    if (args.verbose) {
      for (const auto& s : metrics.rooms) {
        std::printf("|   %-15s | %-5s | gt room %-12s | matched %3d | Dice %.2f | best %.2f |\n",
                    world.name.c_str(), tacs::enumName(runs[m].method), s.id.c_str(),
                    s.matched_room, s.dice, s.best_dice);
      }
      for (const auto& room : runs[m].rooms) {
        std::printf(
            "|   %-15s | %-5s | room %2u %-8s centre (%6.2f, %6.2f) points %zu kf %zu walls",
            world.name.c_str(), tacs::enumName(runs[m].method), room.id,
            tacs::roomKindName(room.kind), room.center.x(), room.center.y(), room.free_space.size(),
            room.keyframe_ids.size());
        for (uint32_t w : room.wall_ids) {
          const auto it = walls.landmarks().find(w);
          if (it == walls.landmarks().end()) continue;
          const Eigen::Vector2d mid = it->second.midpoint();
          std::printf(" %u(n %.0f %.0f at %.2f %.2f)", w, it->second.normal.x(),
                      it->second.normal.y(), mid.x(), mid.y());
        }
        std::printf(" |\n");
      }
    }
    std::fflush(stdout);
  }
  return {runs[0].rooms, runs[1].rooms};
}

}  // namespace

int main(int argc, char** argv) {
  tacs::setUpProcess(argv);
  Args args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--worlds" && i + 1 < argc) {
      args.worlds_dir = argv[++i];
    } else if (a == "--world" && i + 1 < argc) {
      args.worlds.push_back(argv[++i]);
    } else if (a == "--keyframe-distance" && i + 1 < argc) {
      args.keyframe_distance = std::stod(argv[++i]);
    } else if (a == "--config" && i + 1 < argc) {
      args.config = tacs::loadPipelineConfig(argv[++i]).config;
    } else if (a == "--trials" && i + 1 < argc) {
      args.trials = std::max(1, std::stoi(argv[++i]));
    } else if (a == "--verbose") {
      args.verbose = true;
    } else {
      std::printf(
          "Usage: bench_rooms [--worlds DIR] [--world NAME|FILE]... [--keyframe-distance M] "
          "[--config YAML] [--trials K] [--verbose]\nRoom segmentation (tacs and voxel) on "
          "simulated worlds "
          "with ground-truth "
          "poses, scored against the worlds' ground-truth rooms.\n");
      return a == "--help" || a == "-h" ? 0 : 2;
    }
  }
  if (args.worlds_dir.empty()) args.worlds_dir = tacs::bench::findWorldsDir();
  std::vector<std::string> paths;
  if (args.worlds.empty()) {
    for (const auto& e : fs::directory_iterator(args.worlds_dir)) {
      if (e.path().extension() == ".json") paths.push_back(e.path().string());
    }
    std::sort(paths.begin(), paths.end());
  }
  for (const auto& w : args.worlds) {
    paths.push_back(fs::exists(w) ? w : (fs::path(args.worlds_dir) / (w + ".json")).string());
  }
  std::printf(
      "Room segmentation with ground-truth poses, keyframe every %.2f m; "
      "load %s\n\n",
      args.keyframe_distance, tacs::bench::loadAverage().c_str());
  std::printf(
      "| world             | method | kf | rooms est / gt | P | R | F1 | mean Dice | over | "
      "under | ms/kf mean | ms/kf max |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::vector<std::string> consistency;
  for (const auto& p : paths) {
    try {
      std::vector<std::vector<std::vector<tacs::RoomRegion>>> trials(2);  // method -> trial
      for (int t = 1; t <= args.trials; ++t) {
        const auto rooms = runWorld(p, args, static_cast<uint64_t>(t));
        for (size_t m = 0; m < rooms.size(); ++m) {
          trials[m].push_back(tacs::freeSpaceRegions(rooms[m]));
        }
      }
      for (size_t m = 0; m < trials.size() && args.trials > 1; ++m) {
        const tacs::TrialSummary s = tacs::summarizeTrials(trials[m]);
        char row[256];
        std::snprintf(row, sizeof(row), "| %-17s | %-5s | %d | %5.2f | %4.2f | %5.1f |",
                      fs::path(p).stem().c_str(), m == 0 ? "tacs" : "voxel", args.trials, s.n_room,
                      s.sigma_room, 100.0 * s.dcs);
        consistency.push_back(row);
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", p.c_str(), e.what());
      return 1;
    }
  }
  if (!consistency.empty()) {
    std::printf(
        "\nConsistency over trials (noise seeds 1..K): mean room count, its population "
        "standard deviation, DCS between trials (eval/room_metrics.h)\n\n"
        "| world | method | K | N_room | sigma_room | DCS [%%] |\n|---|---|---|---|---|---|\n");
    for (const auto& row : consistency) std::printf("%s\n", row.c_str());
  }
  return 0;
}
