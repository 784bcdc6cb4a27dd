// Backend scale benchmark: a synthetic graph of N keyframes and W walls (default 1000 / 300),
// with drifting odometry, noisy wall observations and a few loop closures. Prints a markdown
// table of the optimisation time, iterations and the error before and after.
//
//   bench_backend [--keyframes N] [--walls W] [--observations-per-keyframe K]
//                 [--incremental 1 --window K]
// --incremental 1: the graph is built keyframe by keyframe and optimised on the backend's
// schedule after each one (optimizationWindow: with --window K > 0, window solves between full
// ones); prints the time per keyframe over the run and over its last 500 keyframes.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "tacs_graphs/backend/factor_graph.h"

namespace {

using tacs::Pose3;

struct Args {
  int keyframes = 1000;
  int walls = 300;
  int observations = 8;
  int threads = 1;  // Ceres threads (the live backend node leaves the other core to odometry)
  int incremental = 0;
  int window = 0;
  tacs::TrustRegion trust_region = tacs::BackendConfig().trust_region;  // the shipped default
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i];
    if (k == "--trust-region") {
      const std::string name = argv[i + 1];
      if (name != "dogleg" && name != "levenberg_marquardt") {
        throw std::invalid_argument("--trust-region: " + tacs::enumChoices<tacs::TrustRegion>());
      }
      a.trust_region =
          name == "dogleg" ? tacs::TrustRegion::kDogleg : tacs::TrustRegion::kLevenbergMarquardt;
      continue;
    }
    const int v = std::stoi(argv[i + 1]);
    if (k == "--keyframes") a.keyframes = v;
    if (k == "--walls") a.walls = v;
    if (k == "--observations-per-keyframe") a.observations = v;
    if (k == "--threads") a.threads = v;
    if (k == "--incremental") a.incremental = v;
    if (k == "--window") a.window = v;
  }
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  const Args args = parse(argc, argv);
  std::mt19937 rng(42);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);

  // Ground truth: a robot sweeping a 60 x 60 m building on a lawn-mower path, a keyframe every
  // metre, odometry drifting about 1%; walls are vertical planes with Manhattan orientations at
  // random offsets.
  std::vector<Pose3> truth;
  for (int i = 0; i < args.keyframes; ++i) {
    const int row = i / 60, col = i % 60;
    const double x = (row % 2 == 0) ? col : 59 - col;
    truth.push_back(tacs::poseFromXyzRpy(x, 2.0 * row, 0.0, 0.0, 0.0, (row % 2 == 0) ? 0 : M_PI));
  }
  std::vector<tacs::WallPlane> walls;
  for (int w = 0; w < args.walls; ++w) {
    walls.push_back({(w % 4) * M_PI / 2, -60.0 * uniform(rng)});
  }

  const bool incremental = args.incremental != 0;
  tacs::BackendConfig config;
  config.max_iterations = incremental ? tacs::BackendConfig().max_iterations : 50;
  config.window_keyframes = args.window;
  config.num_threads = args.threads;
  config.trust_region = args.trust_region;
  tacs::FactorGraph graph(config);
  Pose3 odom = truth[0];
  std::vector<double> per_keyframe_ms;
  size_t since_full = 0;
  int full_solves = 0;
  const Eigen::Matrix<double, 6, 6> info = Eigen::Matrix<double, 6, 6>::Identity() * 400.0;
  for (int i = 0; i < args.keyframes; ++i) {
    if (i > 0) {
      const Pose3 step = truth[i - 1].inverse() * truth[i];
      const Pose3 noisy = step * tacs::poseFromXyzRpy(0.02 * noise(rng), 0.02 * noise(rng), 0.0,
                                                      0.0, 0.0, 0.0005 + 0.002 * noise(rng));
      odom = odom * noisy;
      graph.addKeyframe(i, odom);
      graph.addRelativePose(i - 1, i, noisy, info, false);
    } else {
      graph.addKeyframe(0, odom);
    }
    for (int k = 0; k < args.observations; ++k) {
      // Walls are laid out along the path: a keyframe sees the walls around its own stretch.
      const int base = i * args.walls / args.keyframes - args.observations / 2;
      const uint32_t w = static_cast<uint32_t>(std::clamp(base + k, 0, args.walls - 1));
      const Eigen::Vector3d n_b = truth[i].rotation().transpose() * walls[w].normal();
      const double d_b = walls[w].d + walls[w].normal().dot(truth[i].translation());
      if (!graph.hasWall(w)) {
        const Eigen::Vector3d n_map = odom.rotation() * n_b;
        graph.addWall(w, tacs::WallPlane::fromNormalD(n_map, d_b - n_map.dot(odom.translation())));
      }
      graph.addWallObservation(i, w, n_b, d_b + 0.02 * noise(rng));
    }
    const bool loop = i >= 200 && i % 200 == 0;  // a few loops back to earlier rows
    if (loop)
      graph.addRelativePose(i - 120, i, truth[i - 120].inverse() * truth[i], info * 10, true);
    if (incremental) {
      ++since_full;
      const auto window = tacs::optimizationWindow(config, i + 1, since_full, loop);
      const tacs::OptimizationReport step = graph.optimize(window);
      per_keyframe_ms.push_back(step.time_ms);
      if (!step.window) ++full_solves, since_full = 0;
    }
  }
  const auto rmse = [&]() {
    double sum = 0;
    for (int i = 0; i < args.keyframes; ++i) {
      sum += (graph.keyframePose(i).translation() - truth[i].translation()).squaredNorm();
    }
    return std::sqrt(sum / args.keyframes);
  };
  const double before = rmse();
  const tacs::OptimizationReport report = graph.optimize();
  if (incremental) {
    const auto mean = [&](size_t from) {
      double sum = 0;
      for (size_t i = from; i < per_keyframe_ms.size(); ++i) sum += per_keyframe_ms[i];
      return sum / std::max<size_t>(1, per_keyframe_ms.size() - from);
    };
    const size_t last = per_keyframe_ms.size() > 500 ? per_keyframe_ms.size() - 500 : 0;
    double total = 0;
    for (double ms : per_keyframe_ms) total += ms;
    std::printf(
        "| keyframes | window | full solves | mean ms per keyframe | mean ms, last 500 | max ms "
        "| t_FGO (s) | RMSE after the final full solve (m) |\n");
    std::printf("|---|---|---|---|---|---|---|---|\n");
    std::printf("| %d | %d | %d | %.1f | %.1f | %.1f | %.2f | %.3f |\n", args.keyframes,
                args.window, full_solves, mean(0), mean(last),
                *std::max_element(per_keyframe_ms.begin(), per_keyframe_ms.end()),
                (total + report.time_ms) / 1000.0, rmse());
    return report.usable ? 0 : 1;
  }
  std::printf(
      "| keyframes | walls | wall observations | residual blocks | iterations | t_FGO (ms) "
      "| RMSE before (m) | RMSE after (m) |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  std::printf("| %d | %zu | %d | %zu | %d | %.1f | %.3f | %.3f |\n", args.keyframes,
              graph.wallCount(), args.keyframes * args.observations, report.residual_blocks,
              report.iterations, report.time_ms, before, rmse());
  return report.usable ? 0 : 1;
}
