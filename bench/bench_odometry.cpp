// Benchmark: LidarOdometry throughput on full-resolution VLP-16 scans (16 x 1800 beams, about
// 28k points) rendered in the synthetic box room of the tests, driving at 0.8 m/s while turning.
//
//   bench_odometry [--scans N] [--threads N]
// Prints time per scan (mean, median, max), scans per second and the final drift.
#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "../test/common/box_room.h"  // the scene renderer shared with the unit tests
#include "bench_common.h"
#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/odometry/lidar_odometry.h"
#include "tacs_graphs/odometry/parallel.h"

namespace {

tacs::Pose3 truePose(double t) {
  // A slow figure: forward at 0.8 m/s with a yaw rate swinging between +-0.4 rad/s.
  const double yaw = 1.0 - std::cos(0.5 * t);
  double x = 2.0, y = 2.0;
  const double dt = 0.01;
  for (double s = 0.0; s < t; s += dt) {
    const double a = 1.0 - std::cos(0.5 * s);
    x += 0.8 * std::cos(a) * dt;
    y += 0.8 * std::sin(a) * dt;
  }
  return tacs::poseFromXyzRpy(x, y, 0.5, 0.0, 0.0, yaw);
}

}  // namespace

int main(int argc, char** argv) {
  tacs::setUpProcess(argv);
  int scans = 60;
  tacs::OdometryConfig config;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--scans" && i + 1 < argc) {
      scans = std::max(2, std::atoi(argv[++i]));
    } else if (arg == "--threads" && i + 1 < argc) {
      config.gicp.num_threads = std::max(1, std::atoi(argv[++i]));
    } else {
      std::fprintf(stderr, "usage: %s [--scans N] [--threads N]\n", argv[0]);
      return arg == "--help" ? 0 : 2;
    }
  }
  const tacs::test::BoxRoom room;
  std::vector<tacs::PointCloud> clouds;
  size_t points = 0;
  for (int i = 0; i < scans; ++i) {
    clouds.push_back(tacs::test::renderScan(room, truePose(0.1 * i), i, 16, 1800));
    points += clouds.back().size();
  }
  tacs::LidarOdometry odometry(config);
  std::vector<double> ms;
  int failed = 0, keyframes = 0;
  double registration_ms = 0.0;
  tacs::Stopwatch total;
  for (int i = 0; i < scans; ++i) {
    const tacs::OdometryResult r = odometry.process(0.1 * i, clouds[i]);
    ms.push_back(r.time_ms);
    failed += !r.ok;
    keyframes += r.is_keyframe;
    registration_ms += r.registration.time_ms;
  }
  const double wall_ms = total.elapsedMs();
  const tacs::Pose3 truth = truePose(0.0).inverse() * truePose(0.1 * (scans - 1));
  std::vector<double> sorted = ms;
  std::sort(sorted.begin(), sorted.end());
  std::printf(
      "LidarOdometry on %d synthetic VLP-16 scans (%.0f points each), %d threads "
      "(machine: %d)\n",
      scans, double(points) / scans, tacs::resolveThreads(config.gicp.num_threads),
      omp_get_num_procs());
  std::printf("OpenMP wait policy: %s; 1-minute load average at the end: %s\n\n",
              tacs::openMpWaitPolicy().c_str(), tacs::bench::loadAverage().c_str());
  std::printf(
      "| scans/s | mean ms/scan | median | max | GICP ms/scan | keyframes | failed | "
      "final drift (cm) | final rot. drift (deg) |\n|---|---|---|---|---|---|---|---|---|\n");
  std::printf("| %.1f | %.1f | %.1f | %.1f | %.1f | %d | %d | %.2f | %.3f |\n",
              1000.0 * scans / wall_ms, wall_ms / scans, sorted[sorted.size() / 2], sorted.back(),
              registration_ms / scans, keyframes, failed,
              100.0 * tacs::test::translationError(odometry.pose(), truth),
              tacs::test::rotationErrorDeg(odometry.pose(), truth));
  return 0;
}
