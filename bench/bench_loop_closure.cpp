// bench_loop_closure: CoSG-LCD against the distance-threshold baseline on the simulated worlds
// (paper Table III metrics N_loop, PR_loop, t_LD).
//
//   bench_loop_closure [--world WORLD.json ...] [--spacing M] [--drift SCALE] [--seed N]
//                      [--verbose]   (one line per CoSG-LCD detection)
//
// For each world the simulator renders a VLP-16 keyframe every `spacing` metres (0.5) of the
// ground-truth path; the keyframe clouds are range-cropped and 0.2 m voxel-downsampled as the
// odometry's are. The pose "estimate" is the ground truth corrupted by an odometry-like drift
// that grows with the distance travelled (deterministic seed; see Drift). Loops never feed back
// into the estimate (there is no backend here), so late revisits see the full drift.
//
// Room re-detection is emulated from the ground-truth room polygons: CoSG-LCD runs when the robot
// has gone `trigger_m` (1 m) into a room it has visited before, and every `redetect_m` (10 m)
// while it stays in one room (a single-room lab is re-detected as its segmentation refreshes).
// The room's keyframes are all earlier keyframes inside its polygon. The baselines run on every
// keyframe with d = 1 m and d = 5 m. A loop is true when its relative pose agrees with ground
// truth within 0.3 m and 3 deg (PR_loop of docs/DESIGN.md). t_LD counts detection calls only; the
// one-off preparation of each keyframe cloud (covariances, KD-tree) is printed separately.
#include <pcl/common/transforms.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "bench_common.h"
#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/loop_closure/loop_detector.h"
#include "tacs_graphs/odometry/preprocess.h"
#include "tacs_graphs/sim/scan_stream.h"
#include "tacs_graphs/sim/world.h"

namespace {

using tacs::Pose3;

struct Keyframe {
  uint32_t id = 0;
  double stamp = 0.0;
  Pose3 truth, estimate;
  int room = -1;  // index of the ground-truth room containing it, -1: none
  tacs::PointCloud cloud;
};

/// Odometry-like drift per metre travelled: a constant yaw bias drawn per world plus white yaw
/// and translation noise, integrated along the path (about 1-2 % of the distance).
struct Drift {
  double yaw_bias_deg_per_m = 0.03;
  double yaw_noise_deg_per_sqrt_m = 0.05;
  double translation_noise_per_m = 0.01;
};

double rotationDeg(const Pose3& a, const Pose3& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180.0 / M_PI;
}

std::vector<Keyframe> makeKeyframes(const tacs::sim::World& world, double spacing, Drift drift,
                                    uint64_t seed, double* render_ms) {
  tacs::sim::ScanStream stream(world, tacs::sim::SimOptions{});
  const tacs::Trajectory gt = stream.groundTruth();
  const Pose3 T_base_sensor = stream.baseToSensor();
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double yaw_bias = (rng() % 2 ? 1.0 : -1.0) * drift.yaw_bias_deg_per_m;
  std::vector<Keyframe> out;
  tacs::Stopwatch watch;
  for (size_t i = 0; i < gt.size(); ++i) {
    if (!out.empty() &&
        (gt[i].pose.translation() - out.back().truth.translation()).norm() < spacing) {
      continue;
    }
    Keyframe kf;
    kf.id = static_cast<uint32_t>(out.size());
    kf.stamp = gt[i].stamp;
    kf.truth = gt[i].pose;
    if (out.empty()) {
      kf.estimate = kf.truth;
    } else {
      const Pose3 motion = out.back().truth.inverse() * kf.truth;
      const double d = motion.translation().norm();
      const double yaw_err =
          (yaw_bias * d + drift.yaw_noise_deg_per_sqrt_m * std::sqrt(d) * normal(rng)) * M_PI /
          180.0;
      Pose3 noisy = motion;
      noisy.translation() += drift.translation_noise_per_m * d *
                             Eigen::Vector3d(normal(rng), normal(rng), 0.1 * normal(rng));
      noisy.linear() = Eigen::AngleAxisd(yaw_err, Eigen::Vector3d::UnitZ()) * motion.linear();
      kf.estimate = out.back().estimate * noisy;
    }
    for (size_t r = 0; r < world.rooms.size(); ++r) {
      if (tacs::sim::pointInPolygon(world.rooms[r].polygon, kf.truth.translation().head<2>())) {
        kf.room = static_cast<int>(r);
        break;
      }
    }
    tacs::sim::SimScan scan;
    stream.render(i, &scan);
    tacs::PointCloud cloud = tacs::preprocess(tacs::sim::toPointCloud(scan), {});
    pcl::transformPointCloud(cloud, kf.cloud, T_base_sensor.matrix().cast<float>());
    out.push_back(std::move(kf));
  }
  *render_ms = watch.elapsedMs();
  return out;
}

/// Keyframe indices at which a room re-detection is emulated, with the room's earlier keyframes.
struct Trigger {
  size_t query;
  std::vector<uint32_t> room_keyframes;
};

std::vector<Trigger> roomTriggers(const std::vector<Keyframe>& kfs, double trigger_m,
                                  double redetect_m) {
  std::vector<Trigger> out;
  std::vector<std::vector<uint32_t>> members;
  std::vector<int> visits;
  int current = -1;
  double in_room_m = 0.0, next_at_m = 0.0;
  for (size_t k = 0; k < kfs.size(); ++k) {
    const int room = kfs[k].room;
    if (room >= static_cast<int>(members.size())) {
      members.resize(room + 1);
      visits.resize(room + 1, 0);
    }
    if (room != current) {  // entering a room (or leaving all rooms)
      current = room;
      in_room_m = 0.0;
      if (room >= 0) {
        ++visits[room];
        next_at_m = visits[room] > 1 ? trigger_m : redetect_m;  // first visit: only refreshes
      }
    } else if (k > 0) {
      in_room_m += (kfs[k].truth.translation() - kfs[k - 1].truth.translation()).norm();
    }
    if (room >= 0) {
      members[room].push_back(kfs[k].id);
      if (in_room_m >= next_at_m) {
        out.push_back({k, members[room]});
        next_at_m = in_room_m + redetect_m;
      }
    }
  }
  return out;
}

struct Metrics {
  int loops = 0, true_loops = 0, coarse = 0, fine = 0, detections = 0, registrations = 0;
  double total_ms = 0.0, prepare_ms = 0.0;

  void operator+=(const Metrics& o) {
    loops += o.loops, true_loops += o.true_loops, coarse += o.coarse, fine += o.fine;
    detections += o.detections, registrations += o.registrations;
    total_ms += o.total_ms, prepare_ms += o.prepare_ms;
  }
};

void score(const std::vector<Keyframe>& kfs, const tacs::LoopDetection& d, Metrics* m) {
  for (const tacs::LoopClosure& loop : d.loops) {
    const Pose3 truth = kfs[loop.from].truth.inverse() * kfs[loop.to].truth;
    const bool ok = (truth.translation() - loop.T_from_to.translation()).norm() < 0.3 &&
                    rotationDeg(truth, loop.T_from_to) < 3.0;
    ++m->loops;
    m->true_loops += ok;
    m->coarse += loop.path == tacs::LoopPath::kCoarse;
    m->fine += loop.path == tacs::LoopPath::kFine;
  }
}

void finish(const tacs::LoopDetector& detector, Metrics* m) {
  m->detections = detector.stats().detections;
  m->registrations = detector.stats().registrations;
  m->total_ms = detector.stats().total_ms;
}

bool g_verbose = false;

// One line per CoSG detection: what was searched and how each registration scored.
void printDetection(const tacs::LoopDetector& detector, const std::vector<Keyframe>& kfs,
                    const Trigger& t, const tacs::LoopDetection& d) {
  const Keyframe& q = kfs[t.query];
  std::printf(
      "  query %u (room %d, %zu room keyframes, est. error %.2f m): partitions %d, "
      "candidates %zu, coarse scores",
      q.id, q.room, t.room_keyframes.size(),
      (q.truth.translation() - q.estimate.translation()).norm(), d.partitions, d.candidates.size());
  for (size_t k = 0; k < d.registered.size(); ++k) {
    const Keyframe& c = kfs[d.registered[k]];
    std::printf(" %u:%.2f(%.1fm, truth %.2f)", c.id, d.coarse_scores[k],
                (c.truth.translation() - q.truth.translation()).norm(),
                detector.matchScore(c.id, q.id, c.truth.inverse() * q.truth));
  }
  for (size_t k = 0; k < d.refined.size(); ++k) {
    std::printf(" | refined %u:%.2f", d.refined[k], d.refined_scores[k]);
  }
  for (const tacs::LoopClosure& loop : d.loops) {
    const Pose3 truth = kfs[loop.from].truth.inverse() * kfs[loop.to].truth;
    std::printf(" -> loop %u-%u %s score %.2f err %.3f m %.2f deg", loop.from, loop.to,
                tacs::loopPathName(loop.path), loop.score,
                (truth.translation() - loop.T_from_to.translation()).norm(),
                rotationDeg(truth, loop.T_from_to));
  }
  std::printf("\n");
}

Metrics runCosg(const std::vector<Keyframe>& kfs, const std::vector<Trigger>& triggers) {
  tacs::LoopDetector detector{tacs::LoopClosureConfig()};
  Metrics m;
  size_t next = 0;
  for (size_t k = 0; k < kfs.size(); ++k) {
    tacs::Stopwatch prep;
    detector.addKeyframe(kfs[k].id, kfs[k].stamp, kfs[k].estimate, kfs[k].cloud);
    m.prepare_ms += prep.elapsedMs();
    for (; next < triggers.size() && triggers[next].query == k; ++next) {
      const tacs::LoopDetection d = detector.detectInRoom(kfs[k].id, triggers[next].room_keyframes);
      if (g_verbose) printDetection(detector, kfs, triggers[next], d);
      score(kfs, d, &m);
    }
  }
  finish(detector, &m);
  return m;
}

Metrics runDistance(const std::vector<Keyframe>& kfs, double distance_m) {
  tacs::LoopClosureConfig config;
  config.method = tacs::LoopMethod::kDistance;
  config.distance.distance_threshold_m = distance_m;
  tacs::LoopDetector detector(config);
  Metrics m;
  for (const Keyframe& kf : kfs) {
    tacs::Stopwatch prep;
    detector.addKeyframe(kf.id, kf.stamp, kf.estimate, kf.cloud);
    m.prepare_ms += prep.elapsedMs();
    score(kfs, detector.detectByDistance(kf.id), &m);
  }
  finish(detector, &m);
  return m;
}

void printRow(const std::string& world, const std::string& method, const Metrics& m) {
  const double pr = m.loops ? static_cast<double>(m.true_loops) / m.loops : 0.0;
  std::printf("| %s | %s | %d | %s | %d / %d | %.0f | %d | %.1f | %d |\n", world.c_str(),
              method.c_str(), m.loops, m.loops ? std::to_string(pr).substr(0, 4).c_str() : "-",
              m.coarse, m.fine, m.total_ms, m.detections,
              m.detections ? m.total_ms / m.detections : 0.0, m.registrations);
  std::fflush(stdout);
}

std::vector<std::string> defaultWorlds() {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(__FILE__).parent_path().parent_path() / "worlds";
  std::vector<std::string> out;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() == ".json") out.push_back(entry.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  tacs::setUpProcess(argv);
  std::vector<std::string> worlds;
  double spacing = 0.5, drift_scale = 1.0;
  uint64_t seed = 7;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--world" && i + 1 < argc) {
      worlds.push_back(argv[++i]);
    } else if (arg == "--spacing" && i + 1 < argc) {
      spacing = std::atof(argv[++i]);
    } else if (arg == "--drift" && i + 1 < argc) {
      drift_scale = std::atof(argv[++i]);
    } else if (arg == "--verbose") {
      g_verbose = true;
    } else if (arg == "--seed" && i + 1 < argc) {
      seed = std::strtoull(argv[++i], nullptr, 10);
    } else {
      std::fprintf(stderr,
                   "usage: %s [--world WORLD.json ...] [--spacing M] [--drift SCALE] [--seed N] "
                   "[--verbose]\n",
                   argv[0]);
      return arg == "--help" ? 0 : 2;
    }
  }
  if (worlds.empty()) worlds = defaultWorlds();
  Drift drift;
  drift.yaw_bias_deg_per_m *= drift_scale;
  drift.yaw_noise_deg_per_sqrt_m *= drift_scale;
  drift.translation_noise_per_m *= drift_scale;
  std::printf(
      "Loop detection on simulated worlds: keyframe every %.2f m, drift scale %.2f, seed "
      "%llu; OpenMP wait policy %s\n\n",
      spacing, drift_scale, static_cast<unsigned long long>(seed),
      tacs::openMpWaitPolicy().c_str());
  std::printf(
      "| world | method | N_loop | PR_loop | coarse / fine | t_LD ms | detections | "
      "ms/detection | GICP runs |\n|---|---|---|---|---|---|---|---|---|\n");
  std::vector<std::string> notes;
  Metrics totals[3];
  for (const std::string& path : worlds) {
    const tacs::sim::World world = tacs::sim::loadWorld(path);
    double render_ms = 0.0;
    const std::vector<Keyframe> kfs = makeKeyframes(world, spacing, drift, seed, &render_ms);
    const std::vector<Trigger> triggers = roomTriggers(kfs, 1.0, 10.0);
    double max_drift = 0.0;
    for (const Keyframe& kf : kfs) {
      max_drift = std::max(max_drift, (kf.truth.translation() - kf.estimate.translation()).norm());
    }
    const Metrics cosg = runCosg(kfs, triggers);
    const Metrics near = runDistance(kfs, 1.0), far = runDistance(kfs, 5.0);
    size_t points = 0;
    for (const Keyframe& kf : kfs) points += kf.cloud.size();
    printRow(world.name, "CoSG-LCD", cosg);
    printRow(world.name, "distance d=1 m", near);
    printRow(world.name, "distance d=5 m", far);
    totals[0] += cosg, totals[1] += near, totals[2] += far;
    char note[400];
    std::snprintf(note, sizeof(note),
                  "%s: %zu keyframes, %zu room triggers, max drift %.2f m, end drift %.2f m / "
                  "%.1f deg, %zu points/keyframe, cloud preparation %.1f ms/keyframe",
                  world.name.c_str(), kfs.size(), triggers.size(), max_drift,
                  (kfs.back().truth.translation() - kfs.back().estimate.translation()).norm(),
                  rotationDeg(kfs.back().truth, kfs.back().estimate), points / kfs.size(),
                  cosg.prepare_ms / std::max<size_t>(1, kfs.size()));
    notes.push_back(note);
  }
  if (worlds.size() > 1) {
    printRow("all", "CoSG-LCD", totals[0]);
    printRow("all", "distance d=1 m", totals[1]);
    printRow("all", "distance d=5 m", totals[2]);
  }
  std::printf("\n");
  for (const std::string& n : notes) std::printf("- %s\n", n.c_str());
  std::printf("\n1-minute load average at the end: %s\n", tacs::bench::loadAverage().c_str());
  return 0;
}
