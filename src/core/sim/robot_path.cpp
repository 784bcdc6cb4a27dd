#include "tacs_graphs/sim/robot_path.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "tacs_graphs/sim/sim_random.h"

namespace tacs::sim {
namespace {

constexpr double kStep = 0.02;  // [m] sampling of the path
constexpr double kPi = 3.14159265358979323846;

/// Height of the highest floor under (x, y), false when there is none (a void).
bool floorUnder(const World& world, const Eigen::Vector2d& p, double* z) {
  bool found = false;
  for (const auto& f : world.floors) {
    if ((!found || f.z > *z) && pointInPolygon(f.polygon, p)) *z = f.z, found = true;
  }
  return found;
}

// The waypoints over all laps, densely sampled (z: given, else NaN to be filled from the floor);
// between laps the robot drives back to the first waypoint.
std::vector<Eigen::Vector3d> densePolyline(const World& world, const std::string& name) {
  const TrajectorySpec& spec = world.trajectory;
  std::vector<Eigen::Vector3d> wps;
  for (int lap = 0; lap < spec.laps; ++lap) {
    for (const auto& w : spec.waypoints) {
      if (wps.empty() || (w.head<2>() - wps.back().head<2>()).norm() > 1e-9) wps.push_back(w);
    }
  }
  for (size_t i = 0; i < spec.waypoints.size(); ++i) {
    double z;
    if (!floorUnder(world, spec.waypoints[i].head<2>(), &z)) {
      throw WorldError(name + ": trajectory.waypoints[" + std::to_string(i) +
                       "]: not above any floor");
    }
  }
  std::vector<Eigen::Vector3d> dense;
  for (size_t i = 0; i + 1 < wps.size(); ++i) {
    const double len = (wps[i + 1].head<2>() - wps[i].head<2>()).norm();
    const int n = std::max(1, static_cast<int>(std::ceil(len / kStep)));
    for (int k = 0; k < n; ++k) dense.push_back(wps[i] + (wps[i + 1] - wps[i]) * (double(k) / n));
  }
  dense.push_back(wps.back());
  return dense;
}

}  // namespace

TrajectorySpec startingAtWaypoint(const TrajectorySpec& spec, int k, const std::string& name) {
  const int n = static_cast<int>(spec.waypoints.size());
  if (k < 0 || k >= n) {
    throw WorldError(name + ": start waypoint " + std::to_string(k) + " is not in [0, " +
                     std::to_string(n - 1) + "]");
  }
  TrajectorySpec out = spec;
  if (k == 0) return out;
  const auto& w = spec.waypoints;
  out.waypoints.clear();
  const bool closed = n > 2 && (w.front().head<2>() - w.back().head<2>()).norm() < 1e-6;
  if (closed) {
    for (int i = k; i < n - 1; ++i) out.waypoints.push_back(w[i]);
    for (int i = 0; i <= k; ++i) out.waypoints.push_back(w[i]);
  } else {
    for (int i = k; i < n; ++i) out.waypoints.push_back(w[i]);
    for (int i = n - 2; i >= 0; --i) out.waypoints.push_back(w[i]);
  }
  return out;
}

RobotPath::RobotPath(const World& world, uint64_t seed, const std::string& name) {
  const TrajectorySpec& spec = world.trajectory;
  jitter_rad_ = spec.jitter_deg * kPi / 180.0;
  jitter_z_ = spec.jitter_z_m;
  roundCorners(world, densePolyline(world, name), name);
  computeHeadings();
  // A yaw rate that ramps needs turns sampled finely in angle: the rate is constant along each
  // sample step, and a turn in place may turn tens of degrees in one.
  if (spec.max_yaw_accel_dps2 > 0.0) subdivideTurns(0.25 * kPi / 180.0);
  computeTiming(spec);
  SplitMix rng(mixSeed(seed, 0x70617468));  // "path"
  for (double& p : phase_) p = 2.0 * kPi * rng.uniform();
}

void RobotPath::roundCorners(const World& world, const std::vector<Eigen::Vector3d>& dense,
                             const std::string& name) {
  // Moving average with a window that shrinks at both ends so the path still starts and ends at
  // the first and last waypoints.
  const int half = static_cast<int>(std::round(world.trajectory.corner_radius_m / kStep));
  const int n = static_cast<int>(dense.size());
  std::vector<Eigen::Vector2d> prefix(n + 1, Eigen::Vector2d::Zero());
  for (int i = 0; i < n; ++i) prefix[i + 1] = prefix[i] + dense[i].head<2>();
  samples_.resize(n);
  for (int i = 0; i < n; ++i) {
    const int w = std::min({half, i, n - 1 - i});
    const Eigen::Vector2d xy = (prefix[i + w + 1] - prefix[i - w]) / (2 * w + 1);
    double z = dense[i].z();
    if (!floorUnder(world, xy, &z) && std::isnan(dense[i].z())) {
      std::ostringstream msg;
      msg << name << ": trajectory: the path leaves the floor near (" << xy.x() << ", " << xy.y()
          << ")";
      throw WorldError(msg.str());
    }
    if (!std::isnan(dense[i].z())) z = dense[i].z();
    samples_[i] = Eigen::Vector3d(xy.x(), xy.y(), z);
  }
  arc_.assign(n, 0.0);
  for (int i = 1; i < n; ++i) {
    arc_[i] = arc_[i - 1] + (samples_[i].head<2>() - samples_[i - 1].head<2>()).norm();
  }
  length_ = std::max(arc_.back(), 1e-6);
}

void RobotPath::computeHeadings() {
  // From a short chord around each sample (one-sided at the ends), unwrapped.
  const int n = static_cast<int>(samples_.size());
  const int chord = std::max(1, static_cast<int>(std::round(0.1 / kStep)));
  yaw_.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    const int a = std::max(0, std::min(i - chord, n - 1 - 2 * chord));
    const int b = std::min(n - 1, std::max(0, a) + 2 * chord);
    const Eigen::Vector2d d = samples_[b].head<2>() - samples_[std::max(0, a)].head<2>();
    double yaw = d.norm() > 1e-9 ? std::atan2(d.y(), d.x()) : (i > 0 ? yaw_[i - 1] : 0.0);
    if (i > 0) yaw = yaw_[i - 1] + std::remainder(yaw - yaw_[i - 1], 2.0 * kPi);
    yaw_[i] = yaw;
  }
}

void RobotPath::subdivideTurns(double max_dyaw) {
  std::vector<Eigen::Vector3d> samples{samples_.front()};
  std::vector<double> arc{arc_.front()}, yaw{yaw_.front()};
  for (size_t i = 1; i < samples_.size(); ++i) {
    const int steps =
        std::max(1, static_cast<int>(std::ceil(std::abs(yaw_[i] - yaw_[i - 1]) / max_dyaw)));
    for (int k = 1; k <= steps; ++k) {
      const double f = static_cast<double>(k) / steps;
      samples.push_back(samples_[i - 1] + f * (samples_[i] - samples_[i - 1]));
      arc.push_back(arc_[i - 1] + f * (arc_[i] - arc_[i - 1]));
      yaw.push_back(yaw_[i - 1] + f * (yaw_[i] - yaw_[i - 1]));
    }
  }
  samples_ = std::move(samples);
  arc_ = std::move(arc);
  yaw_ = std::move(yaw);
}

void RobotPath::computeTiming(const TrajectorySpec& spec) {
  // Speed profile: yaw-rate limit per segment, then acceleration limits forward and backward.
  // With a yaw-acceleration limit, the segments whose yaw rate would change faster get a lower
  // rate (and their ends a lower speed), and the profile is made again until none does.
  const int n = static_cast<int>(samples_.size());
  const double max_rate = spec.max_yaw_rate_dps * kPi / 180.0;
  const double max_yaw_accel = spec.max_yaw_accel_dps2 * kPi / 180.0;
  // Arc length and yaw turned over each sample step (index i: from i - 1 to i).
  std::vector<double> step(n, 0.0), turn(n, 0.0);
  for (int i = 1; i < n; ++i) {
    step[i] = arc_[i] - arc_[i - 1];
    turn[i] = std::abs(yaw_[i] - yaw_[i - 1]);
  }
  std::vector<double> speed_cap(n, spec.speed_mps), rate_cap(n, max_rate), v(n), rate(n, 0.0);
  for (int i = 1; i < n; ++i) {
    if (turn[i] > 1e-12) speed_cap[i] = std::min(speed_cap[i], max_rate * step[i] / turn[i]);
  }
  for (int round = 0; round < 50; ++round) {
    v = speed_cap;
    v[0] = v[n - 1] = 0.0;
    for (int pass = 0; pass < 2; ++pass) {
      for (int k = 1; k < n; ++k) {
        const int i = pass == 0 ? k : n - 1 - k, j = pass == 0 ? i - 1 : i + 1;
        const double ds = std::abs(arc_[i] - arc_[j]);
        v[i] = std::min(v[i], std::sqrt(v[j] * v[j] + 2.0 * spec.max_accel_mps2 * ds));
      }
    }
    time_.assign(n, 0.0);
    for (int i = 1; i < n; ++i) {
      const double vm = 0.5 * (v[i] + v[i - 1]);
      // At least as long as the turn takes at the yaw-rate limit (turning in place: ds ~ 0).
      const double dt = std::max(vm > 1e-9 ? step[i] / vm : 0.0, turn[i] / rate_cap[i]);
      time_[i] = time_[i - 1] + dt;
      rate[i] = dt > 0.0 ? turn[i] / dt : 0.0;
    }
    if (max_yaw_accel <= 0.0) return;
    // The yaw rate, as a function of the yaw turned, changes as the speed does along the arc:
    // w^2 by at most 2 alpha per radian, from rest at both ends.
    std::vector<double> limited = rate;
    double before = 0.0;  // at rest before the first segment
    for (int i = 1; i < n; ++i) {
      limited[i] = std::min(limited[i], std::sqrt(before * before + 2.0 * max_yaw_accel * turn[i]));
      before = limited[i];
    }
    double after = 0.0;  // and after the last
    for (int i = n - 1; i >= 1; --i) {
      limited[i] = std::min(limited[i], std::sqrt(after * after + 2.0 * max_yaw_accel * turn[i]));
      after = limited[i];
    }
    bool changed = false;
    for (int i = 1; i < n; ++i) {
      if (limited[i] >= rate[i] * (1.0 - 1e-9) || rate[i] <= 0.0) continue;
      const double dt = turn[i] / std::max(limited[i], 1e-6);
      rate_cap[i] = std::min(rate_cap[i], std::max(limited[i], 1e-6));
      speed_cap[i] = std::min(speed_cap[i], step[i] / dt);
      speed_cap[i - 1] = std::min(speed_cap[i - 1], step[i] / dt);
      changed = true;
    }
    if (!changed) return;
  }
}

Pose3 RobotPath::poseAt(double t) const {
  t = std::clamp(t, 0.0, time_.back());
  const size_t i = std::min<size_t>(
      std::max<size_t>(1, std::upper_bound(time_.begin(), time_.end(), t) - time_.begin()),
      time_.size() - 1);
  const double span = time_[i] - time_[i - 1];
  const double a = span > 0 ? (t - time_[i - 1]) / span : 1.0;
  const Eigen::Vector3d p = samples_[i - 1] + a * (samples_[i] - samples_[i - 1]);
  const double yaw = yaw_[i - 1] + a * (yaw_[i] - yaw_[i - 1]);
  // Vibration: a few incommensurate frequencies with seeded phases (smooth, deterministic).
  auto wobble = [&](int k) {
    return (std::sin(2 * kPi * 1.7 * t + phase_[3 * k]) +
            0.6 * std::sin(2 * kPi * 4.3 * t + phase_[3 * k + 1]) +
            0.4 * std::sin(2 * kPi * 9.1 * t + phase_[3 * k + 2])) /
           2.0;
  };
  return poseFromXyzRpy(p.x(), p.y(), p.z() + jitter_z_ * wobble(2), jitter_rad_ * wobble(0),
                        jitter_rad_ * wobble(1), yaw);
}

}  // namespace tacs::sim
