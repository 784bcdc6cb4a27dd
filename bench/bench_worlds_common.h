// Shared by the benchmarks that score a module on every simulated world with ground-truth poses
// (bench_walls_worlds, bench_traversability_worlds): command line, world discovery, the levelled
// base frame the pipeline works in, and geometric ground-truth labels of scan points (the ray
// caster does not report which primitive it hit).
#pragma once

#include <pcl/common/transforms.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "tacs_graphs/common/types.h"
#include "tacs_graphs/pipeline/pipeline_config.h"
#include "tacs_graphs/sim/scan_stream.h"
#include "tacs_graphs/sim/world.h"

namespace tacs::bench {

struct WorldsArgs {
  std::string worlds_dir;
  std::vector<std::string> worlds;  // --world NAME|FILE; empty: every worlds/*.json
  PipelineConfig config;            // --config FILE, else the defaults
  bool verbose = false;
};

/// Parses --worlds DIR, --world NAME|FILE (repeatable), --config YAML, --verbose. Prints `usage`
/// and returns false on anything else.
inline bool parseWorldsArgs(int argc, char** argv, const char* usage, WorldsArgs* args) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--worlds" && i + 1 < argc) {
      args->worlds_dir = argv[++i];
    } else if (a == "--world" && i + 1 < argc) {
      args->worlds.push_back(argv[++i]);
    } else if (a == "--config" && i + 1 < argc) {
      args->config = loadPipelineConfig(argv[++i]).config;
    } else if (a == "--verbose") {
      args->verbose = true;
    } else {
      std::printf("%s", usage);
      return false;
    }
  }
  return true;
}

/// The worlds/ folder, looked for above the working directory and above the executable.
inline std::string findWorldsDir() {
  namespace fs = std::filesystem;
  std::vector<fs::path> starts = {fs::current_path()};
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) starts.push_back(exe.parent_path());
  for (const auto& start : starts) {
    for (fs::path d = start; !d.empty() && d != d.root_path(); d = d.parent_path()) {
      for (const fs::path& c : {d / "worlds", d / "src" / "tacs_graphs" / "worlds"}) {
        if (fs::exists(c / "smoke.json")) return c.string();
      }
    }
  }
  return "";
}

/// World files to run: the --world arguments (names resolved in the worlds folder), else every
/// .json of the worlds folder, sorted.
/// A world that cannot be found ends the benchmark with a message saying so.
inline std::vector<std::string> worldPaths(WorldsArgs* args) {
  namespace fs = std::filesystem;
  if (args->worlds_dir.empty()) args->worlds_dir = findWorldsDir();
  const auto missing = [](const std::string& why) {
    std::fprintf(stderr, "error: %s (give --worlds DIR, or a world's .json file)\n", why.c_str());
    std::exit(2);
  };
  const std::string where = args->worlds_dir.empty()
                                ? "no worlds/ folder above the working directory or the executable"
                                : "not in " + args->worlds_dir;
  std::vector<std::string> paths;
  if (args->worlds.empty()) {
    if (!fs::is_directory(args->worlds_dir)) missing(where);
    for (const auto& e : fs::directory_iterator(args->worlds_dir)) {
      if (e.path().extension() == ".json") paths.push_back(e.path().string());
    }
    std::sort(paths.begin(), paths.end());
  }
  for (const auto& w : args->worlds) {
    if (fs::exists(w)) {
      paths.push_back(w);
    } else if (const fs::path named = fs::path(args->worlds_dir) / (w + ".json");
               !args->worlds_dir.empty() && fs::exists(named)) {
      paths.push_back(named.string());
    } else {
      missing("world " + w + ": no such file, and " + where);
    }
  }
  return paths;
}

/// The gravity-aligned base frame the pipeline works in: ground-truth position and yaw, the
/// roll/pitch vibration of the robot taken out.
inline Pose3 levelledPose(const Pose3& T_world_base) {
  const Eigen::Vector3d fwd = T_world_base.linear().col(0);
  const Eigen::Vector3d t = T_world_base.translation();
  return poseFromXyzRpy(t.x(), t.y(), t.z(), 0, 0, std::atan2(fwd.y(), fwd.x()));
}

/// A simulated scan in the levelled base frame T_world_level (see levelledPose()).
inline PointCloud levelledCloud(const sim::SimScan& scan, const Pose3& T_base_sensor,
                                const Pose3& T_world_level) {
  PointCloud cloud;
  pcl::transformPointCloud(
      sim::toPointCloud(scan), cloud,
      (T_world_level.inverse() * scan.T_world_base * T_base_sensor).matrix().cast<float>());
  return cloud;
}

/// Ground truth "ground": within `tolerance` (m) of the height of a floor polygon containing the
/// point's xy (world frame). Floors of every level count, the lower level of a drop-off too.
inline bool isGroundPoint(const sim::World& world, const Eigen::Vector3d& p,
                          double tolerance = 0.03) {
  for (const auto& f : world.floors) {
    if (std::abs(p.z() - f.z) <= tolerance && sim::pointInPolygon(f.polygon, p.head<2>())) {
      return true;
    }
  }
  return false;
}

inline double meanOf(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / v.size();
}

inline double ratio(size_t num, size_t den) {
  return den == 0 ? 1.0 : static_cast<double>(num) / static_cast<double>(den);
}

}  // namespace tacs::bench
