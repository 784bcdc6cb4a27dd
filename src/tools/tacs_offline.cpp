// tacs_offline: runs the whole pipeline on a bag (rosbag C++ API, no ROS master) or on a simulated
// world streamed in-process, as fast as the CPU allows, and writes the run folder of
// docs/DESIGN.md. The odometry runs a few scans ahead of the keyframe stages, on a thread of its
// own (offline_sources.h); the results are those of running each scan through in turn.
#include <atomic>
#include <csignal>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "offline_sources.h"
#include "tacs_graphs/common/message_reason.h"
#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/common/trajectory_io.h"
#include "tacs_graphs/eval/trajectory_metrics.h"
#include "tacs_graphs/odometry/parallel.h"
#include "tacs_graphs/pipeline/run_folder.h"
#include "tacs_graphs/pipeline/staged_run_folder.h"
#include "tacs_graphs/relocalization/prior_session.h"
#include "tool_main.h"

namespace {

void printUsage() {
  std::cout
      << "Usage: tacs_offline (--bag FILE [--topic T] | --world WORLD.json [--seed N]\n"
         "                    [--duration S]) [--poses TUM [--poses-frame base|sensor]]\n"
         "                    [--config YAML] --out DIR [--quiet]\n"
         "Runs odometry, traversability, walls, rooms, loop closure and the factor-graph backend\n"
         "on every scan, as fast as the CPU allows, and writes DIR/: trajectory_tum.txt,\n"
         "odometry_tum.txt, scene_graph.json, timing.json, config.json, map.pcd, map.bt,\n"
         "topdown.png (and, with --world, ground_truth_tum.txt and ground_truth.json).\n"
         "--topic T      PointCloud2 topic of the bag (default /velodyne_points)\n"
         "--seed N       simulator noise seed (default: the world's)\n"
         "--duration S   simulate only the first S seconds\n"
         "--start-waypoint K  start the world's trajectory at waypoint K (tacs_sim --help)\n"
         "--poses TUM    take the odometry from this trajectory ('t x y z qx qy qz qw', sorted)\n"
         "               instead of GICP, interpolated at each scan's stamp; scans outside its\n"
         "               time span are skipped and counted. Walls, traversability, rooms, loops\n"
         "               and the backend then run on those poses.\n"
         "--poses-frame  the frame the poses are of: base (default) or sensor\n"
         "--reference TUM  a reference trajectory of the base: ATE against it is printed and\n"
         "               it is kept as DIR/reference_tum.txt\n"
         "--config YAML  configuration (default: built-in defaults = config/default.yaml)\n"
         "--prior RUN_DIR  a run folder of an earlier session (scene_graph.json, map.pcd): the\n"
         "               session relocalizes in it by its rooms; once placed, DIR/ is in the\n"
         "               prior's map frame and scene_graph.json is the prior's graph with this\n"
         "               session merged in (re-observed rooms and walls keep their ids).\n"
         "               DIR/localization.json says whether and where it was placed.\n"
         "--localize-only  with --prior: scene_graph.json is the prior's, byte for byte; the\n"
         "               session's own graph is DIR/session_graph.json\n"
         "The sensor extrinsic comes from the bag's /tf_static (frames.base_frame -> cloud "
         "frame),\n"
         "else from frames.base_to_sensor. Exit status: 0 ok, 1 error, 2 bad command line.\n";
}

struct Options {
  std::string bag, topic = "/velodyne_points", world, config, out, poses, poses_frame = "base",
                   reference, prior;
  tacs::sim::SimOptions sim;
  bool quiet = false, localize_only = false;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--help" || arg == "-h") {
      printUsage();
      std::exit(0);
    } else if (arg == "--bag" && has_value) {
      o.bag = argv[++i];
    } else if (arg == "--topic" && has_value) {
      o.topic = argv[++i];
    } else if (arg == "--world" && has_value) {
      o.world = argv[++i];
    } else if (arg == "--seed" && has_value) {
      o.sim.seed = std::stoull(argv[++i]);
    } else if (arg == "--duration" && has_value) {
      o.sim.duration_s = std::stod(argv[++i]);
    } else if (arg == "--start-waypoint" && has_value) {
      o.sim.start_waypoint = std::stoi(argv[++i]);
    } else if (arg == "--reference" && has_value) {
      o.reference = argv[++i];
    } else if (arg == "--poses" && has_value) {
      o.poses = argv[++i];
    } else if (arg == "--poses-frame" && has_value) {
      o.poses_frame = argv[++i];
      if (o.poses_frame != "base" && o.poses_frame != "sensor") {
        throw std::invalid_argument("--poses-frame must be base or sensor");
      }
    } else if (arg == "--config" && has_value) {
      o.config = argv[++i];
    } else if (arg == "--out" && has_value) {
      o.out = argv[++i];
    } else if (arg == "--prior" && has_value) {
      o.prior = argv[++i];
    } else if (arg == "--localize-only") {
      o.localize_only = true;
    } else if (arg == "--quiet") {
      o.quiet = true;
    } else {
      throw std::invalid_argument("unexpected argument '" + arg + "'");
    }
  }
  if (o.bag.empty() == o.world.empty()) throw std::invalid_argument("give --bag or --world");
  if (o.out.empty()) throw std::invalid_argument("--out is required");
  if (o.localize_only && o.prior.empty())
    throw std::invalid_argument("--localize-only needs --prior");
  return o;
}

/// ATE of the optimised keyframes and of the raw odometry when ground truth exists.
void printAccuracy(const tacs::Pipeline& pipeline, const tacs::Trajectory& ground_truth) {
  if (ground_truth.size() < 3 || pipeline.stats().keyframes < 3) return;
  try {
    const double rate =
        ground_truth.size() > 1
            ? (ground_truth.size() - 1) / (ground_truth.back().stamp - ground_truth.front().stamp)
            : 10.0;
    const double max_dt = 0.5 / rate;
    const auto slam = tacs::computeAte(pipeline.keyframeTrajectory(), ground_truth, max_dt);
    const auto odom = tacs::computeAte(pipeline.odometryTrajectory(), ground_truth, max_dt);
    const auto drift =
        tacs::computeDrift(pipeline.odometryTrajectory(), ground_truth, 10.0, max_dt);
    std::cout << std::fixed << std::setprecision(3) << "[tacs_offline] ATE " << slam.rmse
              << " m (keyframes, optimised), odometry ATE " << odom.rmse << " m, drift "
              << drift.percent << " % per 10 m, path " << tacs::pathLength(ground_truth) << " m\n";
  } catch (const std::exception& e) {
    std::cerr << "[tacs_offline] no accuracy figures: " << e.what() << "\n";
  }
}

/// The prior map of --prior, read before the first scan (a bad one fails at once, naming the
/// file); --out may not be the prior's folder, which is only ever read.
std::unique_ptr<tacs::PriorSession> loadPrior(const Options& o,
                                              const tacs::RelocalizationConfig& config) {
  if (o.prior.empty()) return nullptr;
  std::error_code ec;
  if (std::filesystem::exists(o.out, ec) && std::filesystem::equivalent(o.prior, o.out, ec)) {
    throw std::runtime_error("--out " + o.out + " is the prior's folder; give another");
  }
  return std::make_unique<tacs::PriorSession>(
      tacs::PriorMap::load(o.prior),
      o.localize_only ? tacs::PriorMode::kLocalizeOnly : tacs::PriorMode::kMerge, config);
}

/// How the run folder is written: in the prior's frame once the session is placed in it.
tacs::RunView priorView(const tacs::PriorSession* prior, const tacs::Pipeline& pipeline) {
  tacs::RunView view;
  if (!prior || !prior->localized()) return view;
  view.T_out_map = prior->T_prior_session();
  view.graph = prior->outputGraph(pipeline.sceneGraph());
  if (prior->mode() == tacs::PriorMode::kMerge) view.extra_map_points = prior->prior().points;
  return view;
}

void printLocalization(const tacs::PriorSession& prior) {
  const nlohmann::json j = prior.localizationJson();
  std::cout << "[tacs_offline] " << j["status"].get<std::string>();
  if (prior.localized()) {
    const auto& first = j["first_localization"];
    const std::string by = first["session_room"].is_null() ? std::string("the whole map")
                                                           : "room " + first["session_room"].dump();
    std::cout << std::fixed << std::setprecision(2) << " after "
              << first["distance_m"].get<double>() << " m (" << by << " in prior room "
              << first["prior_room"] << ", score " << first["score"].get<double>() << " against "
              << first["runner_up_score"].get<double>() << "), " << prior.roomPairs().size()
              << " rooms paired";
  }
  std::cout << "; " << j["attempts"] << " attempts, " << j["rejected_hypotheses"]
            << " hypotheses rejected\n";
}

// Ctrl-C stops reading scans and leaves --out as it was; a second one kills at once.
std::atomic<bool> interrupted{false};
extern "C" void onInterrupt(int) {
  interrupted = true;
  std::signal(SIGINT, SIG_DFL);
}

int run(const Options& o) {
  tacs::setMinItemsPerThread(512);  // alone on the cores: split a VLP-16 scan (parallel.h)
  // The run is written beside --out and swapped in whole at the end; --out is checked now.
  tacs::StagedRunFolder out(o.out);
  std::signal(SIGINT, onInterrupt);
  tacs::LoadedPipelineConfig loaded;
  if (!o.config.empty()) loaded = tacs::loadPipelineConfig(o.config);
  for (const auto& key : loaded.unknown_keys) {
    std::cerr << "warning: " << o.config << ": unknown key '" << key << "' is ignored\n";
  }
  // Read whole before the first scan: a bad file fails at once, naming the file and line.
  tacs::Trajectory given_poses;
  if (!o.poses.empty()) {
    given_poses = tacs::readTum(o.poses, /*require_increasing=*/true);
    if (given_poses.size() < 2) throw std::runtime_error(o.poses + ": fewer than 2 poses");
  }
  const tacs::Trajectory reference =
      o.reference.empty() ? tacs::Trajectory() : tacs::readTum(o.reference, true);
  const std::unique_ptr<tacs::PriorSession> prior = loadPrior(o, loaded.config.relocalization);
  double driven_m = 0.0;  // along the odometry, for localization.json
  std::unique_ptr<tacs::tools::ScanSource> source;
  if (!o.bag.empty()) {
    source = std::make_unique<tacs::tools::BagSource>(o.bag, o.topic, loaded.config.frames,
                                                      loaded.config.odometry.point_times);
  } else {
    source = std::make_unique<tacs::tools::WorldSource>(o.world, o.sim,
                                                        loaded.config.odometry.point_times);
  }
  // The odometry runs on a thread of its own, a few scans ahead of the keyframe stages here
  // (Pipeline::odometryOf), and the source is read on a third (OdometryAhead); the pipeline is
  // built there at the first usable scan, when the sensor extrinsic is known, and read here only
  // after that scan came through the queues.
  std::unique_ptr<tacs::Pipeline> pipeline_ptr;
  tacs::tools::OdometryAhead ahead(*source, [&](const tacs::Pose3& T_base_sensor) {
    pipeline_ptr = std::make_unique<tacs::Pipeline>(loaded.config, T_base_sensor);
    if (!given_poses.empty()) {
      pipeline_ptr->useGivenPoses(o.poses_frame == "sensor"
                                      ? tacs::rebaseTrajectory(given_poses, T_base_sensor)
                                      : given_poses);
    }
    return pipeline_ptr.get();
  });
  std::set<std::string> reported;  // each kind of bad scan is reported once
  tacs::Stopwatch watch;
  while (const std::optional<tacs::tools::ScanItem> item = ahead.next()) {
    const size_t k = item->k;
    if (interrupted) {
      throw std::runtime_error("interrupted at scan " + std::to_string(k) + ": nothing written; " +
                               out.path() + " is as it was");
    }
    if (!item->error.empty()) {
      if (reported.insert(tacs::messageReason(item->error)).second) {
        std::cerr << "\n[tacs_offline] scan " << k << " skipped: " << item->error << "\n";
      }
      continue;
    }
    if (!item->no_deskew.empty() && reported.insert("point times: " + item->no_deskew).second) {
      std::cerr << "\n[tacs_offline] scan " << k << ": no deskew: " << item->no_deskew_message
                << "; the scan is used as measured (reported once)\n";
    }
    const tacs::ScanOutcome outcome = pipeline_ptr->takeOdometry(item->odometry);
    if (!outcome.accepted && reported.insert(tacs::messageReason(outcome.error)).second) {
      std::cerr << "\n[tacs_offline] scan " << k << " rejected: " << outcome.error << "\n";
    }
    const tacs::Trajectory& odometry = pipeline_ptr->odometryTrajectory();
    if (outcome.accepted && odometry.size() > 1) {
      driven_m +=
          (odometry.back().pose.translation() - odometry.end()[-2].pose.translation()).norm();
    }
    if (prior && (outcome.rooms > 0 || (outcome.keyframe && prior->wantsMapAttempt(driven_m)))) {
      prior->update(pipeline_ptr->sceneGraph(), pipeline_ptr->keyframeClouds(), item->stamp,
                    driven_m);
    }
    if (!o.quiet && (k % 20 == 0 || k == source->size())) {
      std::cerr << "\r[tacs_offline] scan " << k << "/" << source->size() << "  keyframes "
                << pipeline_ptr->stats().keyframes << "  walls "
                << pipeline_ptr->backend().wallMap().walls().size() << "  rooms "
                << pipeline_ptr->backend().roomCount() << "  " << std::fixed << std::setprecision(1)
                << 1e3 * k / watch.elapsedMs() << " scans/s" << std::flush;
    }
  }
  ahead.finish();  // rethrows what stopped the odometry thread, if anything did
  if (!pipeline_ptr) pipeline_ptr = std::make_unique<tacs::Pipeline>(loaded.config);
  tacs::Pipeline& pipeline = *pipeline_ptr;
  const tacs::PipelineStats& counts = pipeline.stats();
  if (!given_poses.empty() && counts.scans > 0 && counts.scans_outside_poses == counts.scans) {
    throw std::runtime_error(o.poses + ": no scan lies within the poses' time span (" +
                             std::to_string(given_poses.front().stamp) + " to " +
                             std::to_string(given_poses.back().stamp) + " s); nothing written");
  }
  if (counts.scans_outside_poses > 0) {
    std::cerr << "\n[tacs_offline] " << counts.scans_outside_poses << " of " << counts.scans
              << " scans lie outside the time span of " << o.poses << " and were skipped\n";
  }
  if (counts.keyframes == 0) {  // nothing to map: no output that looks like a run
    throw std::runtime_error("no usable scan among " + std::to_string(counts.scans) +
                             (counts.first_rejection.empty()
                                  ? std::string(" (the source held none)")
                                  : " (first reason: " + counts.first_rejection + ")") +
                             "; nothing written to " + o.out);
  }
  pipeline.finish();
  if (prior) {
    prior->finish(pipeline.sceneGraph(), pipeline.keyframeClouds(),
                  pipeline.odometryTrajectory().back().stamp, driven_m);
  }
  const double wall_s = watch.elapsedMs() / 1e3;
  if (!o.quiet) std::cerr << "\n";
  const auto export_ms =
      tacs::writeRunFolder(out.stagingPath(), pipeline, {o.bag.empty() ? o.world : o.bag, wall_s},
                           priorView(prior.get(), pipeline));
  if (prior) prior->writeFiles(out.stagingPath(), pipeline.sceneGraph());
  source->writeGroundTruth(out.stagingPath());
  if (!reference.empty()) tacs::writeTum(out.stagingPath() + "/reference_tum.txt", reference);
  out.commit();
  const tacs::PipelineStats& stats = pipeline.stats();
  const tacs::SceneGraph graph = pipeline.sceneGraph();
  const size_t walls = graph.wallCount();
  std::cout << std::fixed << std::setprecision(2) << "[tacs_offline] " << stats.scans << " scans ("
            << stats.rejected_scans << " rejected, " << stats.deskewed_scans << " deskewed, "
            << stats.odometry_recoveries << " recovered), " << stats.keyframes << " keyframes, "
            << walls << " walls (+" << graph.walls.size() - walls << " other planes), "
            << graph.rooms.size() << " rooms, " << wall_s << " s ("
            << (wall_s > 0 ? stats.scans / wall_s : 0.0) << " scans/s), t_FGO "
            << pipeline.fgoSeconds() << " s (CPU " << pipeline.fgoCpuSeconds() << " s), loops "
            << graph.loops.size() << ", t_LD " << pipeline.ldSeconds() << " s -> " << o.out << "\n";
  std::cout << "[tacs_offline] run folder written in" << std::setprecision(1);
  for (const auto& [name, ms] : export_ms) std::cout << " " << name << " " << ms / 1e3 << " s";
  std::cout << "\n";
  if (prior) printLocalization(*prior);
  printAccuracy(pipeline, reference.empty() ? source->groundTruth() : reference);
  return stats.scans > stats.rejected_scans ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  return tacs::tools::toolMain("tacs_offline", argc, argv, parse, run, printUsage);
}
