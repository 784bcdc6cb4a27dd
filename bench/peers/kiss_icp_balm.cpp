// KISS-ICP on the real BALM hall, for results/real/kiss_icp.md (scripts/peer_kiss_icp.sh builds
// it against a KISS-ICP checkout outside this repository; it is not part of the catkin build).
// Usage: kiss_icp_balm BALM_DIR VOXEL_M OUT_TUM -> TUM poses of every scan; timing on stderr.
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "kiss_icp/pipeline/KissICP.hpp"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: kiss_icp_balm BALM_DIR VOXEL_M OUT_TUM\n";
    return 2;
  }
  const std::string dir = argv[1];
  kiss_icp::pipeline::KISSConfig config;  // the library's defaults but the voxel size
  config.voxel_size = std::stod(argv[2]);
  config.deskew = false;  // the scans carry no per-point time
  kiss_icp::pipeline::KissICP kiss(config);
  std::ifstream list(dir + "/scans.txt");
  std::ofstream out(argv[3]);
  out << std::fixed << std::setprecision(9);
  double total_ms = 0.0, max_ms = 0.0;
  int scans = 0;
  std::string line;
  while (std::getline(list, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string index, file;
    double stamp = 0.0;
    fields >> index >> stamp >> file;
    pcl::PointCloud<pcl::PointXYZI> cloud;
    if (pcl::io::loadPCDFile(dir + "/" + file, cloud) != 0) return 1;
    std::vector<Eigen::Vector3d> points;
    points.reserve(cloud.size());
    for (const auto& p : cloud) {
      if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) {
        points.emplace_back(p.x, p.y, p.z);
      }
    }
    const auto start = std::chrono::steady_clock::now();
    kiss.RegisterFrame(points, {});
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    total_ms += ms;
    max_ms = std::max(max_ms, ms);
    ++scans;
    const Eigen::Vector3d t = kiss.pose().translation();
    const Eigen::Quaterniond q = kiss.pose().unit_quaternion();
    out << stamp << " " << t.x() << " " << t.y() << " " << t.z() << " " << q.x() << " " << q.y()
        << " " << q.z() << " " << q.w() << "\n";
  }
  std::cerr << "scans " << scans << " mean_ms " << total_ms / std::max(scans, 1) << " max_ms "
            << max_ms << "\n";
  return scans > 0 ? 0 : 1;
}
