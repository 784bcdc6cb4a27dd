#include "tacs_graphs/common/trajectory_io.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "tacs_graphs/common/file_io.h"

namespace tacs {

void writeTum(const std::string& path, const Trajectory& trajectory) {
  std::string text;
  char line[256];
  for (const auto& sp : trajectory) {
    const Eigen::Vector3d t = sp.pose.translation();
    const Eigen::Quaterniond q(sp.pose.rotation());
    std::snprintf(line, sizeof(line), "%.9f %.9g %.9g %.9g %.9g %.9g %.9g %.9g\n", sp.stamp, t.x(),
                  t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
    text += line;
  }
  try {
    writeFileAtomically(path, text);  // a crash never leaves a half-written trajectory
  } catch (const std::runtime_error& e) {
    throw TrajectoryIoError(e.what());
  }
}

Trajectory readTum(const std::string& path, bool require_increasing) {
  std::ifstream in(path);
  if (!in) throw TrajectoryIoError(path + ": cannot open file");
  Trajectory out;
  std::string line;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream ss(line);
    double v[8];
    for (int i = 0; i < 8; ++i) {
      if (!(ss >> v[i]) || !std::isfinite(v[i])) {
        throw TrajectoryIoError(path + ": line " + std::to_string(line_no) +
                                ": expected 8 numbers 't x y z qx qy qz qw'");
      }
    }
    std::string rest;
    if (ss >> rest) {
      throw TrajectoryIoError(path + ": line " + std::to_string(line_no) +
                              ": unexpected extra field '" + rest + "'");
    }
    Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    if (q.norm() < 1e-6) {
      throw TrajectoryIoError(path + ": line " + std::to_string(line_no) +
                              ": quaternion has zero norm");
    }
    if (!out.empty() && v[0] == out.back().stamp) continue;  // duplicate stamp: keep the first
    if (require_increasing && !out.empty() && v[0] < out.back().stamp) {
      char stamps[96];
      std::snprintf(stamps, sizeof(stamps), "%.6f is before the previous pose's %.6f", v[0],
                    out.back().stamp);
      throw TrajectoryIoError(path + ": line " + std::to_string(line_no) + ": stamp " + stamps +
                              " (stamps must increase)");
    }
    StampedPose sp;
    sp.stamp = v[0];
    sp.pose.linear() = q.normalized().toRotationMatrix();
    sp.pose.translation() = Eigen::Vector3d(v[1], v[2], v[3]);
    out.push_back(sp);
  }
  return out;
}

}  // namespace tacs
