// bench_walls: time of wall extraction per keyframe, printed as a markdown table.
//
//   bench_walls [--data DIR] [--repeats N] [--draw OUT_DIR]
//
// Clouds: the two real PCL room scans (DIR/pcl_room_scans; without --data the set is found as the
// tests find it, README "Test data") and VLP-16-like ring clouds ray-cast in synthetic rooms (16
// rings over +-15 deg, 0.2 deg azimuth steps, 1 cm range noise). Target: <= 20 ms per VLP-16
// keyframe. With --draw, each real scan is drawn top-down to OUT_DIR/<scan>_walls.png: points grey,
// wall segments in colour with their normal, surfaces seen over (furniture, not walls) as thin
// black lines, the sensor as a circle.
#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "bench_common.h"
#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/viz/canvas.h"
#include "tacs_graphs/viz/scene_graph_drawing.h"
#include "tacs_graphs/walls/wall_extractor.h"

namespace {

using tacs::PointCloud;

struct Box {  // axis-aligned, in the room frame
  Eigen::Vector3d lo, hi;
};

// Distance along the ray to the first surface: the inside of `room` or the outside of a box.
double castRay(const Eigen::Vector3d& o, const Eigen::Vector3d& dir, const Box& room,
               const std::vector<Box>& obstacles) {
  double t_hit = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {  // leaving the room
    if (std::abs(dir[a]) < 1e-12) continue;
    const double t = ((dir[a] > 0 ? room.hi[a] : room.lo[a]) - o[a]) / dir[a];
    if (t > 0) t_hit = std::min(t_hit, t);
  }
  for (const auto& b : obstacles) {  // slab test
    double t0 = 0.0, t1 = t_hit;
    for (int a = 0; a < 3 && t0 <= t1; ++a) {
      if (std::abs(dir[a]) < 1e-12) {
        if (o[a] < b.lo[a] || o[a] > b.hi[a]) t0 = t1 + 1;
        continue;
      }
      double ta = (b.lo[a] - o[a]) / dir[a], tb = (b.hi[a] - o[a]) / dir[a];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    if (t0 <= t1 && t0 > 0) t_hit = std::min(t_hit, t0);
  }
  return t_hit;
}

// A VLP-16 scan from `sensor` (room frame), returned in a base frame at the sensor, turned by yaw.
PointCloud vlp16Scan(const Box& room, const std::vector<Box>& obstacles,
                     const Eigen::Vector3d& sensor, double yaw, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.01);
  PointCloud cloud;
  for (int ring = 0; ring < 16; ++ring) {
    const double el = (-15.0 + 2.0 * ring) * M_PI / 180.0;
    for (int k = 0; k < 1800; ++k) {
      const double az = k * 0.2 * M_PI / 180.0;
      const Eigen::Vector3d dir(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                std::sin(el));
      const double r = castRay(sensor, dir, room, obstacles);
      if (!std::isfinite(r) || r > 100.0) continue;
      // Base frame: origin at the sensor, x axis at `yaw` in the room frame.
      const Eigen::Vector3d p = (r + noise(rng)) * dir;
      pcl::PointXYZI q;
      q.x = static_cast<float>(std::cos(yaw) * p.x() + std::sin(yaw) * p.y());
      q.y = static_cast<float>(-std::sin(yaw) * p.x() + std::cos(yaw) * p.y());
      q.z = static_cast<float>(p.z());
      q.intensity = 0.f;
      cloud.push_back(q);
    }
  }
  return cloud;
}

struct Row {
  std::string name;
  size_t input = 0, downsampled = 0;
  int planes = 0;
  size_t walls = 0, seen_over = 0, horizontal = 0;
  double first_ms = 0, mean_ms = 0, p95_ms = 0, max_ms = 0;
};

Row run(const std::string& name, const std::vector<PointCloud>& clouds, int repeats) {
  const tacs::WallExtractor extractor{tacs::WallExtractionConfig{}};
  Row row;
  row.name = name;
  std::vector<double> times;
  for (int r = 0; r < repeats; ++r) {
    for (const auto& cloud : clouds) {
      const auto res = extractor.extract(cloud);
      if (r == 0 && &cloud == &clouds.front()) row.first_ms = res.time_ms;
      times.push_back(res.time_ms);
      if (r == 0) {
        row.input += res.input_points;
        row.downsampled += res.downsampled_points;
        row.planes += res.planes_found;
        row.walls += res.walls.size();
        row.seen_over += res.seen_over.size();
        row.horizontal += res.horizontal.size();
      }
    }
  }
  const size_t n = clouds.size();
  row.input /= n;
  row.downsampled /= n;
  row.planes /= static_cast<int>(n);
  row.walls /= n;
  row.seen_over /= n;
  row.horizontal /= n;
  std::sort(times.begin(), times.end());
  double sum = 0;
  for (double t : times) sum += t;
  row.mean_ms = sum / times.size();
  row.p95_ms = times[std::min(times.size() - 1, static_cast<size_t>(0.95 * times.size()))];
  row.max_ms = times.back();
  return row;
}

// Top-down picture of a real scan and the walls extracted from it.
void drawWalls(const PointCloud& cloud, const std::string& path) {
  const tacs::WallExtractionResult result =
      tacs::WallExtractor(tacs::WallExtractionConfig{}).extract(cloud);
  Eigen::Vector2d lo(-1.0, -1.0), hi(1.0, 1.0);
  for (const auto& p : cloud.points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
    lo = lo.cwiseMin(Eigen::Vector2d(p.x, p.y));
    hi = hi.cwiseMax(Eigen::Vector2d(p.x, p.y));
  }
  tacs::viz::Canvas canvas(lo.array() - 0.5, hi.array() + 0.5, 0.02);
  for (const auto& p : cloud.points) {
    if (std::isfinite(p.x) && std::isfinite(p.y))
      canvas.fillCircle({p.x, p.y}, 0.01, {0, 0, 0, 40});
  }
  for (size_t i = 0; i < result.walls.size(); ++i) {
    const tacs::WallSegment& w = result.walls[i];
    const tacs::viz::Rgba c = tacs::viz::roomColor(static_cast<uint32_t>(i), 255);
    canvas.drawLine(w.endpoints[0], w.endpoints[1], c, 4.0);
    const Eigen::Vector2d mid = w.midpoint();
    canvas.drawLine(mid, mid + 0.4 * w.normal.head<2>(), c, 2.0);
  }
  for (const tacs::WallSegment& s : result.seen_over) {
    canvas.drawLine(s.endpoints[0], s.endpoints[1], {0, 0, 0, 255}, 1.5);
  }
  canvas.drawCircle({0.0, 0.0}, 0.15, {0, 0, 0, 255}, 2.0);
  canvas.savePng(path);
  std::cerr << "bench_walls: " << result.walls.size() << " walls, " << result.seen_over.size()
            << " surfaces seen over -> " << path << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  std::string data_dir, draw_dir;
  int repeats = 20;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--data" && i + 1 < argc) {
      data_dir = argv[++i];
    } else if (arg == "--draw" && i + 1 < argc) {
      draw_dir = argv[++i];
    } else if (arg == "--repeats" && i + 1 < argc) {
      repeats = std::max(1, std::atoi(argv[++i]));
    } else {
      std::cout << "Usage: bench_walls [--data DIR] [--repeats N] [--draw OUT_DIR]\n"
                   "Times wall extraction (default config) on the PCL room scans in\n"
                   "DIR/pcl_room_scans and on synthetic VLP-16 ring clouds; prints markdown.\n"
                   "--draw writes OUT_DIR/<scan>_walls.png: the real scans top-down with their "
                   "walls.\n";
      return arg == "--help" || arg == "-h" ? 0 : 2;
    }
  }
  const std::string scans_dir = tacs::bench::dataSetDir("pcl_room_scans", data_dir);

  std::vector<Row> rows;
  for (const std::string scan : {"room_scan1.pcd", "room_scan2.pcd"}) {
    if (scans_dir.empty()) break;
    pcl::PointCloud<pcl::PointXYZ> xyz;
    const std::string path = scans_dir + scan;
    if (pcl::io::loadPCDFile(path, xyz) != 0) {
      std::cerr << "bench_walls: cannot read " << path << " (use --data DIR)\n";
      continue;
    }
    PointCloud cloud;
    pcl::copyPointCloud(xyz, cloud);
    rows.push_back(run("PCL " + scan + " (real)", {cloud}, repeats));
    if (!draw_dir.empty()) {
      std::filesystem::create_directories(draw_dir);
      drawWalls(cloud, draw_dir + "/" + std::filesystem::path(scan).stem().string() + "_walls.png");
    }
  }

  // VLP-16 at 0.7 m in a 10 x 8 x 2.8 m room with furniture, 5 poses, building at 30 deg.
  const Box room{{0, 0, 0}, {10, 8, 2.8}};
  const std::vector<Box> furniture = {{{1, 1, 0}, {2.5, 1.8, 0.75}},
                                      {{6, 5, 0}, {8, 6.2, 0.75}},
                                      {{9.4, 2, 0}, {10, 4.5, 2.0}},
                                      {{4.5, 3.5, 0}, {4.9, 3.9, 2.8}}};
  std::vector<PointCloud> room_scans, hall_scans;
  const double poses[][3] = {{2, 2, 0.0}, {5, 4, 0.3}, {7.5, 2.5, 1.2}, {3, 6, 2.5}, {8, 7, -1}};
  uint32_t seed = 1;
  for (const auto& p : poses) {
    room_scans.push_back(vlp16Scan(room, furniture, {p[0], p[1], 0.7}, p[2] + M_PI / 6, seed++));
  }
  // VLP-16 in a 30 x 12 x 4 m hall with pillars: longer walls, sparser rings.
  const Box hall{{0, 0, 0}, {30, 12, 4}};
  std::vector<Box> pillars;
  for (double x = 6; x < 30; x += 6) pillars.push_back({{x, 5.7, 0}, {x + 0.6, 6.3, 4}});
  for (const auto& p : poses) {
    hall_scans.push_back(vlp16Scan(hall, pillars, {p[0] * 3, p[1] * 1.4, 0.7}, p[2], seed++));
  }
  rows.push_back(run("VLP-16 ring cloud, 10x8 m room at 30 deg (5 poses)", room_scans, repeats));
  rows.push_back(
      run("VLP-16 ring cloud, 30x12 m hall with pillars (5 poses)", hall_scans, repeats));

  std::printf(
      "| cloud | input points | after voxel | planes | walls | seen over | horizontal "
      "| first call ms | mean ms | p95 ms | max ms |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& r : rows) {
    std::printf("| %s | %zu | %zu | %d | %zu | %zu | %zu | %.1f | %.2f | %.2f | %.2f |\n",
                r.name.c_str(), r.input, r.downsampled, r.planes, r.walls, r.seen_over,
                r.horizontal, r.first_ms, r.mean_ms, r.p95_ms, r.max_ms);
  }
  std::printf(
      "\nDefault config (voxel 0.1 m), %d repeats per cloud, one thread; target <= 20 ms "
      "per VLP-16 keyframe.\n",
      repeats);
  return 0;
}
