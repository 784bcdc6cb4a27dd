// Traversability benchmark: time per scan of TraversabilityMapper on synthetic scans of an
// office-like room (analytic ray casting), for a VLP-16-like sensor (16 rings x 1800 columns,
// +-15 deg) and an OS0-128-like sensor (128 rings x 1024 columns, +-45 deg), on one core.
// Prints a markdown table.
//
//   bench_traversability [--repeats N] [--resolution M] [--range M]
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "../test/common/synthetic_lidar.h"
#include "tacs_graphs/traversability/traversability_mapper.h"

namespace {

struct Args {
  int repeats = 50;
  double resolution = 0.4;
  double range = 16.0;
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i];
    if (k == "--repeats") a.repeats = std::stoi(argv[i + 1]);
    if (k == "--resolution") a.resolution = std::stod(argv[i + 1]);
    if (k == "--range") a.range = std::stod(argv[i + 1]);
  }
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  const Args args = parse(argc, argv);
  tacs::TraversabilityConfig config;
  config.resolution = args.resolution;
  config.max_range = args.range;
  const tacs::TraversabilityMapper mapper(config);
  const tacs::test::Scene scene = tacs::test::roomScene();

  struct Sensor {
    const char* name;
    tacs::test::LidarModel model;
  };
  const Sensor sensors[] = {{"VLP-16 (16 x 1800, +-15 deg)", tacs::test::LidarModel::vlp16()},
                            {"OS0-128 (128 x 1024, +-45 deg)", tacs::test::LidarModel::os0_128()}};
  std::printf(
      "Traversability per scan, office room scene, resolution %.2f m, range %.1f m, "
      "%d scans per sensor, one core\n\n",
      args.resolution, args.range, args.repeats);
  std::printf(
      "| sensor | points | nodes | traversable | safe | mean [ms] | median [ms] | "
      "max [ms] |\n|---|---|---|---|---|---|---|---|\n");
  for (const Sensor& s : sensors) {
    // Scans along a short path so the grid alignment changes between scans.
    std::vector<tacs::test::SyntheticScan> scans;
    for (int i = 0; i < 10; ++i) {
      const tacs::Pose3 base =
          tacs::poseFromXyzRpy(-2.0 + 0.45 * i, -0.5 + 0.1 * i, 0, 0, 0, 0.07 * i);
      scans.push_back(tacs::test::castScan(scene, s.model,
                                           base * tacs::poseFromXyzRpy(0, 0, 0.8, 0, 0, 0), base,
                                           0.01, static_cast<uint32_t>(i)));
    }
    std::vector<double> ms;
    size_t points = 0, nodes = 0, trav = 0, safe = 0;
    for (int r = 0; r < args.repeats; ++r) {
      const auto& scan = scans[r % scans.size()];
      const tacs::TraversabilityResult res = mapper.process(scan.cloud);
      ms.push_back(res.time_ms);
      points += scan.cloud.size();
      nodes += res.graph.nodes.size();
      trav += res.graph.countTraversable();
      safe += res.graph.countSafe();
    }
    std::vector<double> sorted = ms;
    std::sort(sorted.begin(), sorted.end());
    double mean = 0.0;
    for (double v : ms) mean += v;
    mean /= static_cast<double>(ms.size());
    const double n = static_cast<double>(args.repeats);
    std::printf("| %s | %.0f | %.0f | %.0f | %.0f | %.2f | %.2f | %.2f |\n", s.name, points / n,
                nodes / n, trav / n, safe / n, mean, sorted[sorted.size() / 2], sorted.back());
  }
  return 0;
}
