// tacs_offline: runs the whole pipeline synchronously on a bag (rosbag C++ API, no ROS master) or
// on a simulated world streamed in-process, and writes the run folder of DESIGN.md.
#include <pcl/common/transforms.h>

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <set>
#include <string>

#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/common/trajectory_io.h"
#include "tacs_graphs/eval/trajectory_metrics.h"
#include "tacs_graphs/pipeline/run_folder.h"
#include "tacs_graphs/ros/bag_scan_source.h"
#include "tacs_graphs/sim/ground_truth.h"
#include "tacs_graphs/sim/scan_stream.h"
#include "tool_main.h"

namespace {

void printUsage() {
  std::cout
      << "Usage: tacs_offline (--bag FILE [--topic T] | --world WORLD.json [--seed N]\n"
         "                    [--duration S]) [--config YAML] --out DIR [--quiet]\n"
         "Runs odometry, traversability, walls, rooms, loop closure and the factor-graph backend\n"
         "on every scan, as fast as the CPU allows, and writes DIR/: trajectory_tum.txt,\n"
         "odometry_tum.txt, scene_graph.json, timing.json, config.json, map.pcd, map.bt,\n"
         "topdown.png (and, with --world, ground_truth_tum.txt and ground_truth.json).\n"
         "--topic T      PointCloud2 topic of the bag (default /velodyne_points)\n"
         "--seed N       simulator noise seed (default: the world's)\n"
         "--duration S   simulate only the first S seconds\n"
         "--config YAML  configuration (default: built-in defaults = config/default.yaml)\n"
         "The sensor extrinsic comes from the bag's /tf_static (frames.base_frame -> cloud "
         "frame),\n"
         "else from frames.base_to_sensor. Exit status: 0 ok, 1 error, 2 bad command line.\n";
}

struct Options {
  std::string bag, topic = "/velodyne_points", world, config, out;
  tacs::sim::SimOptions sim;
  bool quiet = false;
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
    } else if (arg == "--config" && has_value) {
      o.config = argv[++i];
    } else if (arg == "--out" && has_value) {
      o.out = argv[++i];
    } else if (arg == "--quiet") {
      o.quiet = true;
    } else {
      throw std::invalid_argument("unexpected argument '" + arg + "'");
    }
  }
  if (o.bag.empty() == o.world.empty()) throw std::invalid_argument("give --bag or --world");
  if (o.out.empty()) throw std::invalid_argument("--out is required");
  return o;
}

/// One scan in the sensor frame, from a bag or the simulator.
struct SensorScan {
  double stamp = 0.0;
  std::string frame_id;
  tacs::PointCloud cloud;
  std::string error;  // the message could not be used
};

class ScanSource {
 public:
  virtual ~ScanSource() = default;
  virtual bool next(SensorScan* scan) = 0;
  virtual size_t size() const = 0;
  /// T_base_sensor for the frame of the first scan.
  virtual tacs::Pose3 baseToSensor(const std::string& frame_id) = 0;
  /// Ground-truth trajectory of the base, empty when the source has none.
  virtual tacs::Trajectory groundTruth() const = 0;
  virtual void writeGroundTruth(const std::string& dir) = 0;
};

class BagSource : public ScanSource {
 public:
  BagSource(const Options& o, const tacs::FramesConfig& frames)
      : bag_(o.bag, o.topic), frames_(frames) {}
  bool next(SensorScan* scan) override {
    tacs::BagScanSource::Scan s;
    if (!bag_.next(&s)) return false;
    scan->stamp = s.stamp;
    scan->frame_id = s.frame_id;
    scan->cloud = std::move(s.cloud);
    scan->error = s.conversion.ok ? "" : s.conversion.error;
    return true;
  }
  size_t size() const override { return bag_.messageCount(); }
  tacs::Pose3 baseToSensor(const std::string& frame_id) override {
    const std::string sensor = frames_.sensor_frame.empty() ? frame_id : frames_.sensor_frame;
    if (const auto T = bag_.lookupTransform(frames_.base_frame, sensor)) {
      std::cerr << "[tacs_offline] extrinsic " << frames_.base_frame << " -> " << sensor
                << " from the bag's TF\n";
      return *T;
    }
    std::cerr << "[tacs_offline] no TF " << frames_.base_frame << " -> " << sensor
              << " in the bag: using frames.base_to_sensor\n";
    return frames_.baseToSensor();
  }
  // Bags written by tacs_sim carry their ground truth; it is kept beside the run.
  tacs::Trajectory groundTruth() const override {
    return bag_.readOdometryTopic("/ground_truth/odom");
  }
  void writeGroundTruth(const std::string& dir) override {
    const tacs::Trajectory gt = groundTruth();
    if (!gt.empty()) tacs::writeTum(dir + "/ground_truth_tum.txt", gt);
  }

 private:
  tacs::BagScanSource bag_;
  tacs::FramesConfig frames_;
};

class WorldSource : public ScanSource {
 public:
  explicit WorldSource(const Options& o)
      : world_(tacs::sim::loadWorld(o.world)), stream_(world_, o.sim) {}
  bool next(SensorScan* scan) override {
    tacs::sim::SimScan s;
    if (!stream_.next(&s)) return false;
    scan->stamp = s.stamp;
    scan->frame_id = "velodyne";
    scan->cloud = tacs::sim::toPointCloud(s);
    return true;
  }
  size_t size() const override { return stream_.scanCount(); }
  tacs::Pose3 baseToSensor(const std::string&) override { return stream_.baseToSensor(); }
  tacs::Trajectory groundTruth() const override { return stream_.groundTruth(); }
  void writeGroundTruth(const std::string& dir) override {
    tacs::writeTum(dir + "/ground_truth_tum.txt", stream_.groundTruth());
    tacs::sim::writeGroundTruth(dir + "/ground_truth.json", tacs::sim::groundTruthOf(world_));
  }

 private:
  tacs::sim::World world_;
  tacs::sim::ScanStream stream_;
};

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

int run(const Options& o) {
  tacs::LoadedPipelineConfig loaded;
  if (!o.config.empty()) loaded = tacs::loadPipelineConfig(o.config);
  for (const auto& key : loaded.unknown_keys) {
    std::cerr << "warning: " << o.config << ": unknown key '" << key << "' is ignored\n";
  }
  std::unique_ptr<ScanSource> source;
  if (!o.bag.empty()) {
    source = std::make_unique<BagSource>(o, loaded.config.frames);
  } else {
    source = std::make_unique<WorldSource>(o);
  }
  // Built at the first usable scan, when the sensor extrinsic is known.
  std::unique_ptr<tacs::Pipeline> pipeline_ptr;
  Eigen::Affine3f base_to_sensor = Eigen::Affine3f::Identity();
  std::set<std::string> reported;  // each kind of bad scan is reported once
  tacs::Stopwatch watch;
  SensorScan scan;
  size_t k = 0;
  while (source->next(&scan)) {
    ++k;
    if (!scan.error.empty()) {
      if (reported.insert(scan.error).second) {
        std::cerr << "\n[tacs_offline] scan " << k << " skipped: " << scan.error << "\n";
      }
      continue;
    }
    if (!pipeline_ptr) {
      const tacs::Pose3 T_base_sensor = source->baseToSensor(scan.frame_id);
      base_to_sensor = T_base_sensor.cast<float>();
      pipeline_ptr = std::make_unique<tacs::Pipeline>(loaded.config, T_base_sensor);
    }
    tacs::PointCloud in_base;
    pcl::transformPointCloud(scan.cloud, in_base, base_to_sensor);
    const tacs::ScanOutcome outcome = pipeline_ptr->processScan(scan.stamp, in_base);
    if (!outcome.accepted && reported.insert(outcome.error).second) {
      std::cerr << "\n[tacs_offline] scan " << k << " rejected: " << outcome.error << "\n";
    }
    if (!o.quiet && (k % 20 == 0 || k == source->size())) {
      std::cerr << "\r[tacs_offline] scan " << k << "/" << source->size() << "  keyframes "
                << pipeline_ptr->stats().keyframes << "  walls "
                << pipeline_ptr->backend().wallMap().walls().size() << "  rooms "
                << pipeline_ptr->backend().roomCount() << "  " << std::fixed << std::setprecision(1)
                << 1e3 * k / watch.elapsedMs() << " scans/s" << std::flush;
    }
  }
  if (!pipeline_ptr) pipeline_ptr = std::make_unique<tacs::Pipeline>(loaded.config);
  tacs::Pipeline& pipeline = *pipeline_ptr;
  pipeline.finish();
  const double wall_s = watch.elapsedMs() / 1e3;
  if (!o.quiet) std::cerr << "\n";
  std::filesystem::create_directories(o.out);
  tacs::writeRunFolder(o.out, pipeline, {o.bag.empty() ? o.world : o.bag, wall_s});
  source->writeGroundTruth(o.out);
  const tacs::PipelineStats& stats = pipeline.stats();
  const tacs::SceneGraph graph = pipeline.sceneGraph();
  const size_t walls = graph.wallCount();
  std::cout << std::fixed << std::setprecision(2) << "[tacs_offline] " << stats.scans << " scans ("
            << stats.rejected_scans << " rejected), " << stats.keyframes << " keyframes, " << walls
            << " walls (+" << graph.walls.size() - walls << " other planes), " << graph.rooms.size()
            << " rooms, " << wall_s << " s (" << (wall_s > 0 ? stats.scans / wall_s : 0.0)
            << " scans/s), t_FGO " << pipeline.fgoSeconds() << " s, loops " << graph.loops.size()
            << ", t_LD " << pipeline.ldSeconds() << " s -> " << o.out << "\n";
  printAccuracy(pipeline, source->groundTruth());
  return stats.scans > stats.rejected_scans ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  return tacs::tools::toolMain("tacs_offline", argc, argv, parse, run, printUsage);
}
