// tacs_sim: renders a world into a bag plus ground truth (no ROS master needed).
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <string>

#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/common/trajectory_io.h"
#include "tacs_graphs/ros/sim_bag_writer.h"
#include "tacs_graphs/sim/ground_truth.h"
#include "tacs_graphs/sim/scan_stream.h"

namespace {
void printUsage() {
  std::cout
      << "Usage: tacs_sim WORLD.json --out DIR [--seed N] [--duration S] [--motion-distortion]\n"
         "                [--start-waypoint K]\n"
         "Simulates the LiDAR of WORLD.json along its trajectory and writes\n"
         "  DIR/sequence.bag          /velodyne_points (PointCloud2: x y z intensity ring time,\n"
         "                            frame velodyne), /tf_static (base_link -> velodyne),\n"
         "                            /ground_truth/odom (nav_msgs/Odometry, frame world)\n"
         "  DIR/ground_truth_tum.txt  base_link pose at every scan (t x y z qx qy qz qw)\n"
         "  DIR/ground_truth.json     the world's rooms and walls\n"
         "--seed N       noise seed (default: the world's sensor.seed); same seed, same bytes\n"
         "--duration S   stop after S seconds (default: the whole trajectory)\n"
         "--motion-distortion  cast every firing from the pose at its own time\n"
         "--start-waypoint K  start the trajectory at waypoint K (a closed path is driven round\n"
         "               back to K, an open one to its end and back to its first waypoint)\n"
         "Exit status: 0 ok, 1 error (bad world file, I/O), 2 bad command line.\n";
}
}  // namespace

int main(int argc, char** argv) {
  std::string world_path, out_dir;
  tacs::sim::SimOptions options;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      const bool has_value = i + 1 < argc;
      if (arg == "--help" || arg == "-h") {
        printUsage();
        return 0;
      } else if (arg == "--out" && has_value) {
        out_dir = argv[++i];
      } else if (arg == "--seed" && has_value) {
        options.seed = std::stoull(argv[++i]);
      } else if (arg == "--duration" && has_value) {
        options.duration_s = std::stod(argv[++i]);
      } else if (arg == "--start-waypoint" && has_value) {
        options.start_waypoint = std::stoi(argv[++i]);
      } else if (arg == "--motion-distortion") {
        options.motion_distortion = true;
      } else if (world_path.empty() && arg.rfind("--", 0) != 0) {
        world_path = arg;
      } else {
        throw std::invalid_argument("unexpected argument '" + arg + "'");
      }
    }
    if (world_path.empty() || out_dir.empty()) throw std::invalid_argument("need WORLD and --out");
  } catch (const std::exception& e) {
    std::cerr << "tacs_sim: " << e.what() << "\n";
    printUsage();
    return 2;
  }
  try {
    const tacs::sim::World world = tacs::sim::loadWorld(world_path);
    tacs::sim::ScanStream stream(world, options);
    std::filesystem::create_directories(out_dir);
    const std::string bag_path = out_dir + "/sequence.bag";
    tacs::Stopwatch watch;
    {
      tacs::SimBagWriter::Options bag_options;
      bag_options.time_field = stream.sensor().time_field;
      bag_options.point_times = stream.sensor().motion_distortion;
      tacs::SimBagWriter writer(bag_path, stream.baseToSensor(), bag_options);
      tacs::sim::SimScan scan;
      size_t k = 0;
      while (stream.next(&scan)) {
        writer.write(scan);
        if (++k % 50 == 0 || k == stream.scanCount()) {
          std::cerr << "\r[tacs_sim] scan " << k << "/" << stream.scanCount() << std::flush;
        }
      }
      std::cerr << "\n";
    }
    tacs::writeTum(out_dir + "/ground_truth_tum.txt", stream.groundTruth());
    tacs::sim::writeGroundTruth(out_dir + "/ground_truth.json", tacs::sim::groundTruthOf(world));
    const double duration = stream.scanCount() / stream.sensor().rate_hz;
    std::cout << std::fixed << std::setprecision(1) << world_path << ": " << stream.scanCount()
              << " scans, " << duration << " s, path " << stream.path().length() << " m, bag "
              << std::filesystem::file_size(bag_path) / 1e6 << " MB, " << watch.elapsedMs() / 1e3
              << " s wall\n";
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
