// Benchmark: the odometry alone on a folder of real scans with reference poses (the BALM hall data
// set, README "Test data": scans.txt lists "index stamp file", poses_tum.txt the reference). Prints
// the ATE after SE(3) alignment, the worst steps against the reference's, the recoveries and the
// time per scan.
//
//   bench_real_odometry [--data DIR] [--config YAML] [--every N] [--steps]
//                       [--min-items-per-thread N]
// --data DIR: the folder holding balm_indoor_hall/ (default: where the tests find it).
// --min-items-per-thread N: a parallel loop wakes the second core for at least N items each
//   (odometry/parallel.h). Default 512, as tacs_offline sets it: the odometry alone on the cores.
//   2048 is the nodes' setting, where six processes share the cores.
#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bench_common.h"
#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/common/trajectory_io.h"
#include "tacs_graphs/eval/trajectory_metrics.h"
#include "tacs_graphs/odometry/lidar_odometry.h"
#include "tacs_graphs/odometry/parallel.h"
#include "tacs_graphs/pipeline/pipeline_config.h"

namespace {

struct ScanEntry {
  double stamp = 0.0;
  std::string file;
};

std::vector<ScanEntry> readScanList(const std::string& dir) {
  std::ifstream in(dir + "/scans.txt");
  if (!in) throw std::runtime_error(dir + "/scans.txt: cannot open");
  std::vector<ScanEntry> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    std::string index;
    ScanEntry e;
    if (ss >> index >> e.stamp >> e.file) out.push_back({e.stamp, dir + "/" + e.file});
  }
  return out;
}

// The reference pose nearest to `stamp` (the reference is stamped at the scans).
const tacs::StampedPose& nearest(const tacs::Trajectory& ref, double stamp) {
  return *std::min_element(ref.begin(), ref.end(), [&](const auto& a, const auto& b) {
    return std::abs(a.stamp - stamp) < std::abs(b.stamp - stamp);
  });
}

}  // namespace

int main(int argc, char** argv) {
  tacs::setUpProcess(argv);
  tacs::setMinItemsPerThread(512);  // alone on the cores, as in tacs_offline
  std::string data_dir, config_path;
  int every = 1;
  bool steps = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--data" && i + 1 < argc) {
      data_dir = argv[++i];
    } else if (a == "--config" && i + 1 < argc) {
      config_path = argv[++i];
    } else if (a == "--every" && i + 1 < argc) {
      every = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--min-items-per-thread" && i + 1 < argc) {
      tacs::setMinItemsPerThread(std::max(1, std::atoi(argv[++i])));
    } else if (a == "--steps") {
      steps = true;
    } else {
      std::fprintf(stderr,
                   "usage: bench_real_odometry [--data DIR] [--config YAML] [--every N] "
                   "[--steps] [--min-items-per-thread N]\n");
      return 2;
    }
  }
  std::string dir = tacs::bench::dataSetDir("balm_indoor_hall", data_dir);
  if (dir.empty()) return 1;
  if (dir.back() == '/') dir.pop_back();
  try {
    tacs::PipelineConfig config;
    if (!config_path.empty()) config = tacs::loadPipelineConfig(config_path).config;
    const tacs::Trajectory reference = tacs::readTum(dir + "/poses_tum.txt", true);
    const std::vector<ScanEntry> scans = readScanList(dir);
    tacs::LidarOdometry odometry(config.odometry);
    tacs::Trajectory estimate;
    std::vector<double> times;
    size_t recoveries = 0, rejected = 0;
    for (size_t k = 0; k < scans.size(); k += every) {
      tacs::PointCloud cloud;
      if (pcl::io::loadPCDFile(scans[k].file, cloud) != 0) {
        throw std::runtime_error(scans[k].file + ": cannot read");
      }
      const tacs::OdometryResult r = odometry.process(scans[k].stamp, cloud);
      times.push_back(r.time_ms);
      recoveries += r.recovered;
      if (!r.ok) {
        ++rejected;
        std::printf("scan %zu rejected: %s\n", k, r.error.c_str());
        continue;
      }
      if (steps && !estimate.empty()) {
        const tacs::Pose3 est_step = estimate.back().pose.inverse() * r.T_odom_base;
        const tacs::Pose3 ref_step = nearest(reference, estimate.back().stamp).pose.inverse() *
                                     nearest(reference, r.stamp).pose;
        const tacs::Pose3 err = ref_step.inverse() * est_step;
        std::printf("scan %3zu  step %.2f m %5.1f deg  error %.3f m %5.2f deg  fit %.2f%s\n", k,
                    ref_step.translation().norm(), tacs::rotationAngleDeg(ref_step),
                    err.translation().norm(), tacs::rotationAngleDeg(err), r.fit,
                    r.recovered ? "  recovered" : "");
      }
      estimate.push_back({r.stamp, r.T_odom_base});
    }
    const tacs::AteResult ate = tacs::computeAte(estimate, reference, 0.05);
    std::sort(times.begin(), times.end());
    double sum = 0.0;
    for (double t : times) sum += t;
    std::printf(
        "| data | scans | rejected | recoveries | ATE m | max m | path m | mean ms | "
        "median ms | max ms |\n|---|---|---|---|---|---|---|---|---|---|\n");
    std::printf("| %s | %zu | %zu | %zu | %.3f | %.3f | %.1f | %.1f | %.1f | %.1f |\n",
                dir.substr(dir.find_last_of('/') + 1).c_str(), times.size(), rejected, recoveries,
                ate.rmse, ate.max, tacs::pathLength(reference), sum / times.size(),
                times[times.size() / 2], times.back());
    std::printf("load average %s, OMP_WAIT_POLICY %s, %lld items per thread\n",
                tacs::bench::loadAverage().c_str(), tacs::openMpWaitPolicy().c_str(),
                static_cast<long long>(tacs::minItemsPerThread()));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
