// bench_traversability_worlds: ground segmentation of TraversabilityMapper on the simulated
// worlds, scored point by point against geometric ground truth.
//
//   bench_traversability_worlds [--worlds DIR] [--world NAME|FILE]... [--config YAML]
//                               [--every N] [--verbose]
//
// Every N-th scan (default 5) of each world is rendered, turned into the levelled base frame with
// the ground-truth pose and given to TraversabilityMapper::process(). A point is ground truth
// "ground" when it lies within 3 cm of the height of a floor polygon containing it (world frame;
// the lower level of a drop-off counts). Precision: share of the points the mapper calls ground
// that are ground truth ground. Recall: share of the ground-truth ground points inside the
// mapper's grid (|x|, |y| <= max_range, farther than min_range) that the mapper calls ground;
// "R level" counts only ground within 0.5 m of the robot's floor. Timing: mean process() time.
// Every processed graph also goes into a TraversableMap (map = world frame); traversable map
// nodes that lie over no floor polygon of their level (the void of a drop-off, beyond a railing)
// are counted, and the ones more than 0.2 m from any floor of their level.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <tuple>
#include <vector>

#include "bench_common.h"
#include "bench_worlds_common.h"
#include "tacs_graphs/traversability/traversability_mapper.h"
#include "tacs_graphs/traversability/traversable_map.h"

namespace {

using tacs::Pose3;
using tacs::bench::isGroundPoint;

struct WorldScore {
  size_t scans = 0;
  size_t predicted = 0, true_positive = 0;  // mapper ground points, of which ground truth ground
  size_t truth = 0, found = 0;              // ground truth ground in the grid, of which found
  size_t truth_level = 0, found_level = 0;  // the same for ground at the robot's level
  std::vector<double> ms;
  size_t void_nodes = 0, deep_void_nodes = 0, traversable_nodes = 0;
  // --verbose: missed ground by horizontal range (< 3, < 6, < 10, >= 10 m); false ground by
  // height above the nearest floor below (< 6 cm, < 15 cm, >= 15 cm or over no floor).
  size_t missed_by_range[4] = {0, 0, 0, 0};
  size_t false_by_height[3] = {0, 0, 0};
};

// A traversable node over no floor of its level; "deep" when the floor is more than `margin`
// away in each of 8 directions (a node whose triangle only straddles a floor edge is not deep).
void countVoidNodes(const tacs::sim::World& world, const tacs::TravGraph& graph, double margin,
                    bool verbose, WorldScore* score) {
  constexpr double kLevelTolerance = 0.3;  // [m] a node stands on floors this close in height
  for (const auto& node : graph.nodes) {
    if (!node.traversable) continue;
    ++score->traversable_nodes;
    if (isGroundPoint(world, node.position, kLevelTolerance)) continue;
    ++score->void_nodes;
    bool deep = true;
    for (int k = 0; k < 8 && deep; ++k) {
      const double a = k * M_PI / 4.0;
      const Eigen::Vector3d q =
          node.position + margin * Eigen::Vector3d(std::cos(a), std::sin(a), 0);
      deep = !isGroundPoint(world, q, kLevelTolerance);
    }
    score->deep_void_nodes += deep;
    if (deep && verbose) {
      std::printf("|   traversable node over the void at (%.2f, %.2f, %.2f)%s |\n",
                  node.position.x(), node.position.y(), node.position.z(),
                  node.inferred ? ", inferred" : "");
    }
  }
}

WorldScore runWorld(const std::string& path, const tacs::bench::WorldsArgs& args, size_t every) {
  const tacs::sim::World world = tacs::sim::loadWorld(path);
  tacs::sim::ScanStream stream(world, tacs::sim::SimOptions{});
  const Pose3 T_base_sensor = stream.baseToSensor();
  const tacs::TraversabilityConfig& config = args.config.traversability;
  const tacs::TraversabilityMapper mapper(config);
  tacs::TraversableMap map(config);
  WorldScore score;
  tacs::sim::SimScan scan;
  for (size_t i = 0; i < stream.scanCount(); i += every) {
    stream.render(i, &scan);
    const Pose3 T_world_level = tacs::bench::levelledPose(scan.T_world_base);
    const tacs::PointCloud cloud = tacs::bench::levelledCloud(scan, T_base_sensor, T_world_level);
    const tacs::TraversabilityResult result = mapper.process(cloud);
    score.ms.push_back(result.time_ms);
    map.insert(result.graph, T_world_level, static_cast<uint32_t>(score.scans++));

    const double robot_z = T_world_level.translation().z();
    for (const auto& p : result.ground->points) {
      const Eigen::Vector3d w = T_world_level * Eigen::Vector3d(p.x, p.y, p.z);
      score.predicted++;
      if (isGroundPoint(world, w)) {
        score.true_positive++;
      } else {
        score.false_by_height[isGroundPoint(world, w, 0.06)   ? 0
                              : isGroundPoint(world, w, 0.15) ? 1
                                                              : 2]++;
      }
    }
    // The mapper returns copies of the input points, so a point is "found" when its exact
    // coordinates are among the returned ground points.
    std::vector<Eigen::Vector3f> ground(result.ground->size());
    for (size_t k = 0; k < ground.size(); ++k) {
      ground[k] = result.ground->points[k].getVector3fMap();
    }
    auto less = [](const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
      return std::tie(a.x(), a.y(), a.z()) < std::tie(b.x(), b.y(), b.z());
    };
    std::sort(ground.begin(), ground.end(), less);
    for (const auto& p : cloud.points) {
      if (!std::isfinite(p.x) || std::abs(p.x) > config.max_range ||
          std::abs(p.y) > config.max_range || std::hypot(p.x, p.y) < config.min_range) {
        continue;
      }
      const Eigen::Vector3d w = T_world_level * Eigen::Vector3d(p.x, p.y, p.z);
      if (!isGroundPoint(world, w)) continue;
      const bool found = std::binary_search(ground.begin(), ground.end(),
                                            Eigen::Vector3f(p.getVector3fMap()), less);
      const bool level = std::abs(w.z() - robot_z) < 0.5;
      score.truth++;
      score.found += found;
      score.truth_level += level;
      score.found_level += level && found;
      const double r = std::hypot(p.x, p.y);
      if (!found) score.missed_by_range[r < 3 ? 0 : r < 6 ? 1 : r < 10 ? 2 : 3]++;
    }
  }
  countVoidNodes(world, map.graph(), 0.2, args.verbose, &score);
  return score;
}

}  // namespace

int main(int argc, char** argv) {
  tacs::setUpProcess(argv);
  tacs::bench::WorldsArgs args;
  size_t every = 5;
  std::vector<char*> rest = {argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--every" && i + 1 < argc) {
      every = std::max(1, std::stoi(argv[++i]));
    } else {
      rest.push_back(argv[i]);
    }
  }
  const char* usage =
      "Usage: bench_traversability_worlds [--worlds DIR] [--world NAME|FILE]... [--config YAML] "
      "[--every N] [--verbose]\nGround-point precision / recall of TraversabilityMapper on the "
      "simulated worlds (ground-truth poses), traversable map nodes over the void.\n";
  if (!tacs::bench::parseWorldsArgs(static_cast<int>(rest.size()), rest.data(), usage, &args)) {
    return 2;
  }
  std::printf("Traversability on the simulated worlds, every %zu-th scan; load %s, OpenMP %s\n\n",
              every, tacs::bench::loadAverage().c_str(), tacs::openMpWaitPolicy().c_str());
  std::printf(
      "| world | scans | ground P | ground R | R level | ms/scan | traversable map nodes | over "
      "the void | > 0.2 m into the void |\n|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& path : tacs::bench::worldPaths(&args)) {
    try {
      const WorldScore s = runWorld(path, args, every);
      std::printf("| %-17s | %4zu | %5.3f | %5.3f | %5.3f | %6.1f | %6zu | %4zu | %4zu |\n",
                  std::filesystem::path(path).stem().c_str(), s.scans,
                  tacs::bench::ratio(s.true_positive, s.predicted),
                  tacs::bench::ratio(s.found, s.truth),
                  tacs::bench::ratio(s.found_level, s.truth_level), tacs::bench::meanOf(s.ms),
                  s.traversable_nodes, s.void_nodes, s.deep_void_nodes);
      if (args.verbose) {
        std::printf(
            "|   points: predicted %zu, true %zu (false within 6 cm %zu, 15 cm %zu, farther %zu); "
            "truth %zu, found %zu (missed at < 3 m %zu, 3-6 m %zu, 6-10 m %zu, >= 10 m %zu) |\n",
            s.predicted, s.true_positive, s.false_by_height[0], s.false_by_height[1],
            s.false_by_height[2], s.truth, s.found, s.missed_by_range[0], s.missed_by_range[1],
            s.missed_by_range[2], s.missed_by_range[3]);
      }
      std::fflush(stdout);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", path.c_str(), e.what());
      return 1;
    }
  }
  return 0;
}
