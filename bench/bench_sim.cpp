// bench_sim: LiDAR simulation speed (single thread). Prints one table row per world and sensor:
// primitives, rays per sweep, returns per sweep, ms per sweep and sweeps per second.
//   bench_sim [WORLD.json ...]
// Without arguments it uses a generated office floor of 200 primitives (the speed target: one
// VLP-16 sweep in under 5 ms).
#include <cstdio>
#include <string>
#include <vector>

#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/sim/ray_caster.h"
#include "tacs_graphs/sim/scan_stream.h"

namespace {

using tacs::sim::World;

/// A grid of 5 x 4 rooms (6 x 5 m, doors in every wall) furnished with boxes: 200 primitives.
World officeFloor() {
  World w;
  w.name = "office_200";
  const int nx = 5, ny = 4;
  const double sx = 6.0, sy = 5.0, door = 1.0;
  auto wallWithDoor = [&](Eigen::Vector2d a, Eigen::Vector2d b) {
    const Eigen::Vector2d mid = 0.5 * (a + b), d = (b - a).normalized();
    tacs::sim::Wall w1, w2;
    w1.from = a, w1.to = mid - 0.5 * door * d;
    w2.from = mid + 0.5 * door * d, w2.to = b;
    w.walls.push_back(w1);
    w.walls.push_back(w2);
  };
  for (int i = 0; i <= nx; ++i) {
    for (int j = 0; j < ny; ++j) wallWithDoor({i * sx, j * sy}, {i * sx, (j + 1) * sy});
  }
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i < nx; ++i) wallWithDoor({i * sx, j * sy}, {(i + 1) * sx, j * sy});
  }
  const tacs::sim::Polygon2 outline = {{0, 0}, {nx * sx, 0}, {nx * sx, ny * sy}, {0, ny * sy}};
  w.floors.push_back({outline, 0.0, 0.3});
  w.ceilings.push_back({outline, 2.8, 0.5});
  for (int k = 0; w.walls.size() + w.boxes.size() + 2 < 200; ++k) {
    const int room = k % (nx * ny), slot = k / (nx * ny);
    const double x = (room % nx) * sx + 1.2 + 1.8 * (slot % 3);
    const double y = (room / nx) * sy + 1.0 + 3.0 * (slot / 3 % 2);
    w.boxes.push_back({Eigen::Vector3d(x, y, 0.4), Eigen::Vector3d(0.8, 0.6, 0.8), 15.0 * k, 0.7});
  }
  // Through the doors of the middle row.
  w.trajectory.waypoints = {{1.5, 7.5, NAN}, {28.5, 7.5, NAN}};
  return w;
}

void bench(const World& world, const std::string& model) {
  World w = world;
  if (!model.empty()) tacs::sim::applySensorPreset(model, &w.sensor);
  tacs::sim::ScanStream stream(w, tacs::sim::SimOptions{});
  tacs::sim::RayCaster caster(w);
  const size_t n = std::min<size_t>(stream.scanCount(), 50);
  const size_t step = std::max<size_t>(1, stream.scanCount() / n);
  tacs::sim::SimScan scan;
  size_t returns = 0;
  tacs::Stopwatch watch;
  for (size_t k = 0; k < n; ++k) {
    stream.render(k * step, &scan);
    returns += scan.points.size();
  }
  const double ms = watch.elapsedMs() / n;
  // Ray casting alone (no noise, no point output) from the same poses.
  std::vector<Eigen::Vector3d> dirs;
  const double half = 0.5 * w.sensor.vfov_deg * M_PI / 180.0;
  const int columns = static_cast<int>(std::round(360.0 / w.sensor.hres_deg));
  for (int c = 0; c < columns; ++c) {
    for (int r = 0; r < w.sensor.rings; ++r) {
      const double el = -half + 2.0 * half * r / std::max(1, w.sensor.rings - 1);
      const double az = 2.0 * M_PI * c / columns;
      dirs.emplace_back(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
    }
  }
  const auto gt = stream.groundTruth();
  tacs::sim::RayHit hit;
  watch.restart();
  for (size_t k = 0; k < n; ++k) {
    const tacs::Pose3 T = gt[k * step].pose * stream.baseToSensor();
    for (const auto& d : dirs) caster.cast(T.translation(), T.linear() * d, 100.0, &hit);
  }
  const double cast_ms = watch.elapsedMs() / n;
  const int rays = w.sensor.rings * static_cast<int>(std::round(360.0 / w.sensor.hres_deg));
  std::printf("| %-18s | %-8s | %5zu | %6d | %6zu | %7.2f | %7.1f | %7.2f |\n", w.name.c_str(),
              w.sensor.model.c_str(), caster.primitiveCount(), rays, returns / n, ms, 1e3 / ms,
              cast_ms);
}

}  // namespace

int main(int argc, char** argv) {
  std::printf(
      "| world              | sensor   | prims | rays   | points | ms/scan | scans/s | cast ms "
      "|\n");
  std::printf(
      "|--------------------|----------|-------|--------|--------|---------|---------|---------|"
      "\n");
  if (argc < 2) {
    const World office = officeFloor();
    for (const char* model : {"vlp16", "os1_64", "os0_128"}) bench(office, model);
    return 0;
  }
  for (int i = 1; i < argc; ++i) {
    try {
      bench(tacs::sim::loadWorld(argv[i]), "");
    } catch (const std::exception& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
      return 1;
    }
  }
  return 0;
}
