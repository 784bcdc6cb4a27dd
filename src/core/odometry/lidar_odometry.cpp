#include "tacs_graphs/odometry/lidar_odometry.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <type_traits>

#include "tacs_graphs/common/config.h"
#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/odometry/parallel.h"

namespace tacs {

void OdometryConfig::validate() const {
  preprocess.validate();
  gicp.validate();
  requireConfig(keyframe_distance_m > 0.0, "odometry.keyframe_distance_m", "must be > 0");
  requireConfig(keyframe_angle_deg > 0.0, "odometry.keyframe_angle_deg", "must be > 0");
  requireConfig(local_map_keyframes >= 1, "odometry.local_map_keyframes", "must be >= 1");
  requireConfig(local_map_voxel_m > 0.0, "odometry.local_map_voxel_m", "must be > 0");
  requireConfig(local_map_covariances == "neighbours" || local_map_covariances == "carried",
                "odometry.local_map_covariances", "must be neighbours or carried");
  requireConfig(min_scan_points >= 3 * gicp.k_neighbors, "odometry.min_scan_points",
                "must be >= 3 * gicp.k_neighbors");
  requireConfig(max_time_gap_s > 0.0, "odometry.max_time_gap_s", "must be > 0");
  requireConfig(recovery_correspondence_distance_m > 0.0,
                "odometry.recovery_correspondence_distance_m", "must be > 0");
  requireConfig(refine_correspondence_distance_m >= 0.0,
                "odometry.refine_correspondence_distance_m", "must be >= 0 (0 = off)");
  requireConfig(refine_robust_plane_distance_m >= 0.0, "odometry.refine_robust_plane_distance_m",
                "must be >= 0 (0 = least squares)");
  requireConfig(wide_gate_max_points >= 0, "odometry.wide_gate_max_points",
                "must be >= 0 (0 = all points)");
  requireConfig(min_inlier_ratio >= 0.0 && min_inlier_ratio <= 1.0, "odometry.min_inlier_ratio",
                "must be in [0, 1]");
  requireConfig(max_correction_m > 0.0, "odometry.max_correction_m", "must be > 0");
  requireConfig(max_correction_deg > 0.0, "odometry.max_correction_deg", "must be > 0");
  requireConfig(max_adaptive_correction_m >= max_correction_m, "odometry.max_adaptive_correction_m",
                "must be >= max_correction_m");
  requireConfig(max_adaptive_correction_deg >= max_correction_deg,
                "odometry.max_adaptive_correction_deg", "must be >= max_correction_deg");
  requireConfig(fit_distance_m > 0.0, "odometry.fit_distance_m", "must be > 0");
  requireConfig(recovery_min_fit >= 0.0 && recovery_min_fit <= 1.0, "odometry.recovery_min_fit",
                "must be in [0, 1]");
  requireConfig(recovery_voxel_m >= 0.0, "odometry.recovery_voxel_m", "must be >= 0");
  requireConfig(recovery_coarse_iterations >= 1, "odometry.recovery_coarse_iterations",
                "must be >= 1");
  requireConfig(recovery_relative_fit >= 0.0 && recovery_relative_fit <= 1.0,
                "odometry.recovery_relative_fit", "must be in [0, 1]");
  requireConfig(recovery_min_gain >= 0.0 && recovery_min_gain <= 1.0, "odometry.recovery_min_gain",
                "must be in [0, 1]");
  requireConfig(recovery_max_angular_accel_dps2 > 0.0, "odometry.recovery_max_angular_accel_dps2",
                "must be > 0");
  requireConfig(level_max_tilt_deg > 0.0 && level_max_tilt_deg < 90.0,
                "odometry.level_max_tilt_deg", "must be in (0, 90)");
  point_times.validate();
  requireConfig(keyframe_cloud_voxel_m >= 0.0, "odometry.keyframe_cloud_voxel_m", "must be >= 0");
}

namespace {

std::string format(const char* fmt, double a, double b, double c = 0.0, double d = 0.0) {
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer), fmt, a, b, c, d);
  return buffer;
}

// The registration cloud deskewed anew (`cloud`, from `before`'s points deskewed with `from`):
// the covariances are carried along rather than searched again (redeskewCovariances).
GicpCloud::ConstPtr redeskewed(const PointCloud& cloud, const GicpCloud& before,
                               const std::vector<float>& times, const BodyVelocity& from,
                               const BodyVelocity& to) {
  std::vector<Eigen::Vector3d> points;
  points.reserve(cloud.size());
  for (const auto& p : cloud.points) points.emplace_back(p.x, p.y, p.z);
  return GicpCloud::fromParts(std::move(points),
                              redeskewCovariances(before.covariances(), times, from, to));
}

}  // namespace

LidarOdometry::LidarOdometry(const OdometryConfig& config) : config_(config) {
  config_.validate();
  if (config_.local_map_covariances == "carried") {
    carried_map_ =
        std::make_unique<CarriedVoxelMap>(config_.local_map_voxel_m, config_.gicp.num_threads);
  }
}

Pose3 LidarOdometry::predict(double stamp, bool* reset) const {
  const double dt = stamp - last_stamp_;
  // A gap is judged against the sensor's own rate too: a 1 Hz recording is no gap at every scan.
  *reset = !has_velocity_ || dt > std::max(config_.max_time_gap_s, 3.0 * scan_interval_s_);
  if (*reset) return last_pose_;
  return last_pose_ * motionOver(velocity_, dt);
}

bool LidarOdometry::isKeyframe(const Pose3& T_odom_base) const {
  if (window_.empty()) return true;
  const Pose3 motion = window_.back().T_odom_base.inverse() * T_odom_base;
  return motion.translation().norm() >= config_.keyframe_distance_m ||
         rotationAngleDeg(motion) >= config_.keyframe_angle_deg;
}

void LidarOdometry::addKeyframe(OdometryResult* result, const GicpCloud::ConstPtr& scan_gicp,
                                const PointCloud::Ptr& cloud) {
  Keyframe kf;
  kf.id = next_keyframe_id_++;
  kf.T_odom_base = last_pose_;  // the registered instant: the local map's frame
  kf.cloud = cloud;
  kf.gicp = scan_gicp;
  if (!window_.empty()) {
    // Information of the motion since the previous keyframe: the GICP Hessian of this scan
    // against that keyframe's scan at their estimated relative pose.
    const Keyframe& prev = window_.back();
    Gicp pair(config_.gicp);
    pair.setTarget(prev.gicp);
    pair.setSource(scan_gicp);
    result->information = pair.evaluate(prev.T_odom_base.inverse() * kf.T_odom_base).information;
  }
  result->is_keyframe = true;
  result->keyframe_id = kf.id;
  result->keyframe_cloud = cloud;
  if (carried_map_) carried_map_->add(kf.id, kf.T_odom_base, *kf.gicp);
  window_.push_back(std::move(kf));
  while (window_.size() > static_cast<size_t>(config_.local_map_keyframes)) {
    if (carried_map_) carried_map_->remove(window_.front().id);
    window_.pop_front();
  }
  rebuildLocalMap();
}

GicpCloud::ConstPtr LidarOdometry::coarseMap() const {
  // The coarse passes align to the local map on their own grid: its voxels' covariances are
  // merged, not searched, and a wide gate then searches a few thousand map points, not all.
  if (!coarse_map_) {
    coarse_map_ = config_.recovery_voxel_m > config_.local_map_voxel_m
                      ? mergeGicpClouds({{Pose3::Identity(), local_map_}}, config_.recovery_voxel_m,
                                        config_.gicp.num_threads)
                      : local_map_;
  }
  return coarse_map_;
}

void LidarOdometry::rebuildLocalMap() {
  coarse_map_.reset();
  if (carried_map_) {
    local_map_ = carried_map_->cloud();
    return;
  }
  PointCloud merged;
  for (const Keyframe& kf : window_) {
    const Eigen::Affine3f T = kf.T_odom_base.cast<float>();
    for (const auto& p : kf.cloud->points) {
      pcl::PointXYZI q = p;
      q.getVector3fMap() = T * p.getVector3fMap();
      merged.points.push_back(q);
    }
  }
  local_map_ = GicpCloud::build(voxelDownsample(merged, config_.local_map_voxel_m),
                                config_.gicp.k_neighbors, config_.gicp.num_threads);
}

PointCloud LidarOdometry::compensate(const PointCloud& scan, const std::vector<float>* offsets,
                                     const BodyVelocity& velocity, bool* deskewed) const {
  *deskewed = usableTimes(scan, offsets);
  if (!*deskewed) return scan;
  return tacs::deskew(scan, *offsets, velocity);
}

GicpResult LidarOdometry::alignTo(const GicpCloud::ConstPtr& target,
                                  const GicpCloud::ConstPtr& scan, double gate_m, const Pose3& from,
                                  double robust_m, int max_iterations,
                                  const std::vector<float>* sweep_times) const {
  GicpConfig gated = config_.gicp;
  gated.max_correspondence_distance_m = gate_m;
  gated.robust_plane_distance_m = robust_m;
  gated.max_iterations = max_iterations;
  Gicp gicp(gated);
  gicp.setTarget(target);
  gicp.setSource(scan);
  if (sweep_times) gicp.setSourceTimes({sweep_times->begin(), sweep_times->end()});
  return gicp.align(from);
}

double LidarOdometry::fitOf(const GicpCloud::ConstPtr& scan, const Pose3& T) const {
  GicpConfig gated = config_.gicp;
  gated.max_correspondence_distance_m = config_.fit_distance_m;
  Gicp gicp(gated);
  gicp.setTarget(local_map_);
  gicp.setSource(scan);
  return gicp.inlierRatio(T);
}

bool LidarOdometry::withinLimits(const Pose3& guess, const Pose3& T) const {
  // The guess's recent error widens the limits (3 sigma), between the configured floor and
  // ceiling: a wheeled robot keeps 1 m / 30 deg, a hand-held sensor's turns get up to 90 deg.
  const double limit_m =
      std::clamp(3.0 * model_error_m_, config_.max_correction_m, config_.max_adaptive_correction_m);
  const double limit_deg =
      std::clamp(3.0 * model_error_rad_ * 180.0 / M_PI, config_.max_correction_deg,
                 config_.max_adaptive_correction_deg);
  const Pose3 correction = guess.inverse() * T;
  return correction.translation().norm() <= limit_m && rotationAngleDeg(correction) <= limit_deg;
}

bool LidarOdometry::reachableIn(double dt, const Pose3& guess, const Pose3& T) const {
  return rotationAngleDeg(guess.inverse() * T) <=
         0.5 * config_.recovery_max_angular_accel_dps2 * dt * dt;
}

GicpResult LidarOdometry::recoverFromHypotheses(const PointCloud& cloud,
                                                const GicpCloud::ConstPtr& scan,
                                                const GicpCloud::ConstPtr& fine_source,
                                                const Pose3& guess) const {
  // Coarse to fine from each yaw about the base's z axis: a sparse source under the wide gate
  // finds the basin, the full scan under the normal gate settles in it; the hypothesis whose
  // result fits most of the scan wins (ties: the smaller turn, listed first).
  const GicpCloud::ConstPtr sparse =
      GicpCloud::build(voxelDownsample(cloud, config_.recovery_voxel_m), config_.gicp.k_neighbors,
                       config_.gicp.num_threads);
  const GicpCloud::ConstPtr coarse_map = coarseMap();
  const double wide_m = std::max(config_.recovery_correspondence_distance_m,
                                 config_.gicp.max_correspondence_distance_m);
  GicpResult best;
  double best_fit = -1.0;
  // About the odom frame's vertical through the guess (a hand-held sensor turns about gravity,
  // not about its own tilted axis), from the constant-velocity guess and from standing still:
  // at a low rate a hand-held turn often reverses, and the velocity then points the wrong way.
  std::vector<Pose3> starts;
  for (const Pose3& base : {guess, last_pose_}) {
    for (double yaw_deg : config_.recovery_yaw_deg) {
      Pose3 start = base;
      start.linear() =
          Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).matrix() *
          base.linear();
      starts.push_back(start);
    }
  }
  // The coarse alignments are independent and each too small to split across threads
  // (parallel.h), so they run side by side; the fine passes follow, best coarse fit first (ties:
  // in the listed order).
  const int n = static_cast<int>(starts.size());
  std::vector<Pose3> coarse(starts.size());
  std::vector<double> coarse_fit(starts.size());
#pragma omp parallel for num_threads(resolveThreads(config_.gicp.num_threads)) schedule(dynamic, 1)
  for (int i = 0; i < n; ++i) {
    coarse[i] = alignTo(coarse_map, sparse, wide_m, starts[i], config_.gicp.robust_plane_distance_m,
                        config_.recovery_coarse_iterations)
                    .T_target_source;
    coarse_fit[i] = fitOf(sparse, coarse[i]);
  }
  std::vector<int> order(starts.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return coarse_fit[a] > coarse_fit[b]; });
  for (int i : order) {
    if (coarse_fit[i] <= best_fit) continue;  // the fine pass rarely gains what the coarse lacks
    GicpResult fine = align(fine_source, config_.gicp.max_correspondence_distance_m, coarse[i],
                            config_.gicp.robust_plane_distance_m);
    const double fit = fitOf(scan, fine.T_target_source);
    if (fit > best_fit) best_fit = fit, best = fine;
  }
  return best;
}

GicpResult LidarOdometry::registerScan(const GicpCloud::ConstPtr& scan, const PointCloud& cloud,
                                       const std::vector<float>* sweep_times, const Pose3& guess,
                                       bool reset, double dt, OdometryResult* result) const {
  const double gate_m = config_.gicp.max_correspondence_distance_m;
  const double robust_m = config_.gicp.robust_plane_distance_m;
  // The wide gates only have to reach the narrow gate's basin: a subset of a dense scan does.
  std::vector<float> subset_times;
  const GicpCloud::ConstPtr wide = wideGateSource(scan, sweep_times, &subset_times);
  Pose3 start = guess;
  if (reset) {  // no motion prior: a coarse pass with wide gating widens the basin
    start =
        align(wide, std::max(config_.recovery_correspondence_distance_m, gate_m), guess, robust_m)
            .T_target_source;
  }
  GicpResult reg = align(wide, gate_m, start, robust_m,
                         wide == scan || !sweep_times ? sweep_times : &subset_times);
  result->fit = fitOf(scan, reg.T_target_source);
  // A rectangular room has false minima a quarter turn away that still fit half the scan: the
  // fit is judged against the recent scans' too, not only against the absolute floor.
  const double min_fit =
      std::max(config_.recovery_min_fit, config_.recovery_relative_fit * recent_fit_);
  const bool plausible = withinLimits(guess, reg.T_target_source);
  if (result->fit < min_fit || !plausible) {
    GicpResult recovered = recoverFromHypotheses(cloud, scan, wide, guess);
    const double fit = fitOf(scan, recovered.T_target_source);
    // A plausible registration (within the motion limits) that merely fits a little less than
    // usual is kept unless a hypothesis fits clearly better: in repetitive stacks and aisles the
    // view turned by 180 deg fits about as well, and a tie must not flip the map. Nor does a
    // hypothesis the carrier cannot reach replace it: at 1.5 m/s through library_stacks the
    // view turned by 180 deg once fitted 0.754 against 0.702, 0.1 s after the last scan; a
    // hand-held sensor at 1 Hz may well have turned by 60 deg.
    const double gain = plausible ? config_.recovery_min_gain : 0.0;
    const bool reachable = !plausible || reset || reachableIn(dt, guess, recovered.T_target_source);
    if (reachable && fit > result->fit + gain) {
      reg = recovered;
      result->fit = fit;
      result->recovered = true;
    }
  }
  return reg;
}

GicpCloud::ConstPtr LidarOdometry::wideGateSource(const GicpCloud::ConstPtr& scan,
                                                  const std::vector<float>* sweep_times,
                                                  std::vector<float>* subset_times) const {
  const double refine_m = config_.refine_correspondence_distance_m;
  const bool refined = refine_m > 0.0 && refine_m < config_.gicp.max_correspondence_distance_m;
  const size_t budget = static_cast<size_t>(std::max(0, config_.wide_gate_max_points));
  if (!refined || budget == 0 || scan->size() <= budget) return scan;
  // Every stride-th point: the subset covers the scan as evenly as the scan's own order does.
  const size_t stride = (scan->size() + budget - 1) / budget;
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Matrix3d> covariances;
  points.reserve(budget);
  covariances.reserve(budget);
  for (size_t i = 0; i < scan->size(); i += stride) {
    points.push_back(scan->points()[i]);
    covariances.push_back(scan->covariances()[i]);
    if (sweep_times) subset_times->push_back((*sweep_times)[i]);
  }
  return GicpCloud::fromParts(std::move(points), std::move(covariances));
}

void LidarOdometry::updateMotionModel(double stamp, const Pose3& guess, const Pose3& pose,
                                      bool reset) {
  const double dt = stamp - last_stamp_;
  const Pose3 step = last_pose_.inverse() * pose;
  velocity_ = velocityOf(step, dt);
  has_velocity_ = true;
  scan_interval_s_ = scan_interval_s_ > 0.0 ? 0.9 * scan_interval_s_ + 0.1 * dt : dt;
  if (!reset) {  // the guess's error, as a running RMS over about the last 10 scans
    const Pose3 error = guess.inverse() * pose;
    const double e_m = error.translation().norm(), e_rad = rotationAngleDeg(error) * M_PI / 180.0;
    model_error_m_ = std::sqrt(0.9 * model_error_m_ * model_error_m_ + 0.1 * e_m * e_m);
    model_error_rad_ = std::sqrt(0.9 * model_error_rad_ * model_error_rad_ + 0.1 * e_rad * e_rad);
  }
  last_pose_ = pose;
  last_stamp_ = stamp;
}

void LidarOdometry::updateRecentFit(double fit) {
  recent_fit_ = recent_fit_ > 0.0 ? 0.8 * recent_fit_ + 0.2 * fit : fit;
}

void LidarOdometry::startOn(double stamp, const PointCloud::Ptr& cloud,
                            const GicpCloud::ConstPtr& scan_gicp, OdometryResult* result) {
  initialized_ = true;
  last_stamp_ = stamp;
  last_pose_ = Pose3::Identity();
  if (config_.level_from_floor) {
    FloorSearch search;
    search.max_tilt_deg = config_.level_max_tilt_deg;
    result->floor = findFloor(*cloud, search);
    if (result->floor) last_pose_.linear() = levellingRotation(result->floor->normal);
  }
  result->T_odom_base = last_pose_;
  addKeyframe(result, scan_gicp, cloud);
}

void LidarOdometry::refineOnNarrowGate(const GicpCloud::ConstPtr& scan_gicp,
                                       const std::vector<float>* sweep_times,
                                       GicpResult* registration) const {
  const double refine_m = config_.refine_correspondence_distance_m;
  if (refine_m <= 0.0 || refine_m >= config_.gicp.max_correspondence_distance_m) return;
  // The inlier test stays on the wide gate's pairs: the narrow gate leaves out far points by
  // design.
  const GicpResult refined = align(scan_gicp, refine_m, registration->T_target_source,
                                   config_.refine_robust_plane_distance_m, sweep_times);
  registration->T_target_source = refined.T_target_source;
  registration->sweep_velocity = refined.sweep_velocity;
}

std::string LidarOdometry::rejection(const Pose3& guess, bool reset,
                                     const OdometryResult& result) const {
  const GicpResult& reg = result.registration;
  if (reg.inlier_ratio < config_.min_inlier_ratio) {
    return format("registration rejected: inlier ratio %.2f < %.2f", reg.inlier_ratio,
                  config_.min_inlier_ratio);
  }
  if (!reset && !result.recovered && !withinLimits(guess, reg.T_target_source)) {
    const Pose3 correction = guess.inverse() * reg.T_target_source;
    return format(
        "registration rejected: it moved the constant-velocity guess by %.2f m "
        "and %.1f deg (beyond the adaptive limits, floor %.2f m, %.1f deg)",
        correction.translation().norm(), rotationAngleDeg(correction), config_.max_correction_m,
        config_.max_correction_deg);
  }
  return "";
}

double LidarOdometry::sweepReference(const PointCloud& scan, const std::vector<float>* offsets,
                                     std::vector<float>* shifted) const {
  if (!config_.deskew || !config_.deskew_to_mid_sweep || !offsets ||
      offsets->size() != scan.size() || scan.empty()) {
    return 0.0;
  }
  const auto [lo, hi] = std::minmax_element(offsets->begin(), offsets->end());
  const float mid = 0.5f * (*lo + *hi);
  shifted->resize(offsets->size());
  for (size_t i = 0; i < offsets->size(); ++i) (*shifted)[i] = (*offsets)[i] - mid;
  return mid;
}

OdometryResult LidarOdometry::process(double stamp, const PointCloud& scan,
                                      const std::vector<float>* point_offsets_s) {
  // Not owned: the scan and its times outlive this call.
  const auto borrowed = [](const auto* p) {
    using T = std::remove_pointer_t<decltype(p)>;
    return p ? std::shared_ptr<T>(std::shared_ptr<T>(), p) : nullptr;
  };
  return process(prepare(stamp, borrowed(&scan), borrowed(point_offsets_s)));
}

PreparedScan LidarOdometry::prepare(double stamp, std::shared_ptr<const PointCloud> scan,
                                    std::shared_ptr<const std::vector<float>> offsets) const {
  Stopwatch watch;
  PreparedScan p;
  p.stamp = stamp;
  p.raw = std::move(scan);
  p.raw_offsets = std::move(offsets);
  // The scan is registered at its sweep's middle (deskew_to_mid_sweep): ref_s is that instant
  // and mid_offsets the point times relative to it.
  p.ref_s = sweepReference(*p.raw, p.raw_offsets.get(), &p.mid_offsets);
  // Preprocessed first, deskewed after (process): each voxel centroid keeps its returns' mean
  // time, so a dense scan is deskewed (twice with deskew_refine) at the cost of its voxels, not
  // its returns.
  p.has_times = usableTimes(*p.raw, p.offsets());
  p.reduced = preprocess(*p.raw, config_.preprocess, &p.stats, p.has_times ? p.offsets() : nullptr,
                         &p.times);
  // The covariances of the scan as measured; process() carries them into the deskewed scan
  // (redeskewCovariances): within a point's few neighbours the motion is a rotation of the plane.
  if (tooFewPoints(p.reduced.size(), p.stats).empty()) {
    p.gicp = GicpCloud::build(p.reduced, config_.gicp.k_neighbors, config_.gicp.num_threads);
  }
  p.time_ms = watch.elapsedMs();
  return p;
}

OdometryResult LidarOdometry::process(const PreparedScan& prepared) {
  Stopwatch watch;
  OdometryResult result;
  const double stamp = prepared.stamp;
  const PointCloud& scan = *prepared.raw;
  result.stamp = stamp;
  result.T_odom_base = stamp_pose_;
  result.preprocess = prepared.stats;
  auto finish = [&](const std::string& error) {
    result.ok = error.empty();
    result.error = error;
    // The scan's whole cost, wherever its preparation ran.
    result.time_ms = prepared.time_ms + watch.elapsedMs();
    return result;
  };
  if (!std::isfinite(stamp)) return finish("non-finite stamp");
  if (initialized_ && stamp <= last_scan_stamp_) {
    return finish(
        format("stamp %.6f is not after the previous scan's %.6f", stamp, last_scan_stamp_));
  }
  const double ref_s = prepared.ref_s;
  const std::vector<float>* offsets = prepared.offsets();
  const double t = stamp + ref_s;
  bool reset = !initialized_;
  const Pose3 guess = initialized_ ? predict(t, &reset) : Pose3::Identity();
  result.motion_prior_reset = reset && initialized_;
  // Deskewed with the guessed motion; without a motion prior the scan stays as measured.
  BodyVelocity velocity;
  if (!reset) velocity = velocity_;
  const bool has_times = prepared.has_times;
  const PointCloud& reduced = prepared.reduced;
  const std::vector<float>& times = prepared.times;
  PointCloud::Ptr cloud(new PointCloud(
      compensate(reduced, has_times ? &times : nullptr, velocity, &result.deskewed)));
  // The preprocessed points' times, when the registration estimates the sweep's motion.
  const bool timed = result.deskewed && config_.sweep_motion;
  const std::vector<float>* sweep_times = timed ? &times : nullptr;
  const std::string too_few = tooFewPoints(cloud->size(), result.preprocess);
  if (!too_few.empty()) return finish(too_few);
  GicpCloud::ConstPtr scan_gicp =
      !prepared.gicp ? GicpCloud::build(*cloud, config_.gicp.k_neighbors, config_.gicp.num_threads)
      : result.deskewed ? redeskewed(*cloud, *prepared.gicp, times, BodyVelocity(), velocity)
                        : prepared.gicp;

  if (!initialized_) {  // the first scan defines the odom frame
    startOn(t, cloud, scan_gicp, &result);
    last_scan_stamp_ = stamp;
    stamp_pose_ = last_pose_;
    attachKeyframeCloud(scan, nullptr, velocity, ref_s != 0.0, &result);
    return finish("");
  }

  result.registration =
      registerScan(scan_gicp, *cloud, sweep_times, guess, reset, t - last_stamp_, &result);
  // The motion the registered cloud is deskewed with.
  BodyVelocity sweep_velocity = velocity;
  if (result.deskewed && config_.deskew_refine) {
    sweep_velocity =
        deskewWithRegisteredMotion(t, reduced, times, velocity, timed, &result, &cloud, &scan_gicp);
  }
  refineOnNarrowGate(scan_gicp, sweep_times, &result.registration);
  const std::string rejected = rejection(guess, reset, result);
  if (!rejected.empty()) return finish(rejected);
  const GicpResult& reg = result.registration;
  updateMotionModel(t, guess, reg.T_target_source, reset);
  updateRecentFit(result.fit);
  last_scan_stamp_ = stamp;
  // Back from the sweep's middle to the stamp with the step's velocity, the refined pose's. The
  // velocity the registered cloud was deskewed with comes from the wide-gate pose, before the
  // refinement: carrying the pose and the keyframe cloud with it placed them as the registration
  // did, but its error reached the stamp (ramped 1.5 m/s worlds: market_hall 8.4 -> 15.7 mm,
  // library_stacks 13.4 -> 19.2 mm keyframe ATE; lab_room 2.76 -> 2.62 mm).
  stamp_pose_ = last_pose_ * motionOver(velocity_, -ref_s);
  result.T_odom_base = stamp_pose_;
  if (isKeyframe(last_pose_)) {
    addKeyframe(&result, scan_gicp, cloud);
    // The dense keyframe cloud is deskewed to the stamp (with the step's velocity, as the pose)
    // when the scan was registered at its sweep's middle, else as the registered cloud was.
    if (ref_s != 0.0) {
      attachKeyframeCloud(scan, prepared.raw_offsets.get(), velocity_, true, &result);
    } else {
      attachKeyframeCloud(scan, result.deskewed ? offsets : nullptr, sweep_velocity, false,
                          &result);
    }
  }
  return finish("");
}

std::string LidarOdometry::tooFewPoints(size_t points, const PreprocessStats& s) const {
  if (points >= static_cast<size_t>(config_.min_scan_points)) return "";
  const std::string counts = std::to_string(s.input) + " points in, " +
                             std::to_string(s.non_finite) + " non-finite, " +
                             std::to_string(s.out_of_range) + " out of range";
  if (points == 0) return "empty scan after preprocessing (" + counts + ")";
  return "too few points after preprocessing (" + std::to_string(points) + " < " +
         std::to_string(config_.min_scan_points) + "; " + counts + ")";
}

BodyVelocity LidarOdometry::deskewWithRegisteredMotion(double t, const PointCloud& reduced,
                                                       const std::vector<float>& times,
                                                       const BodyVelocity& velocity, bool timed,
                                                       OdometryResult* result,
                                                       PointCloud::Ptr* cloud,
                                                       GicpCloud::ConstPtr* scan_gicp) const {
  // Deskewed once more with the motion the registration found (the sweep's own, or the step
  // since the last scan), so the refinement after it sees the scan as that motion measured it.
  const double dt = t - last_stamp_;
  const Pose3 step = last_pose_.inverse() * result->registration.T_target_source;
  const Eigen::Matrix<double, 6, 1>& extra = result->registration.sweep_velocity;
  BodyVelocity sweep_velocity = velocityOf(step, dt);
  if (timed && !result->recovered) {
    sweep_velocity = velocity;
    sweep_velocity.linear += extra.head<3>();
    sweep_velocity.angular += extra.tail<3>();
  }
  result->registration.sweep_velocity.setZero();  // taken into the cloud
  cloud->reset(new PointCloud(compensate(reduced, &times, sweep_velocity, &result->deskewed)));
  *scan_gicp = redeskewed(**cloud, **scan_gicp, times, velocity, sweep_velocity);
  return sweep_velocity;
}

void LidarOdometry::attachKeyframeCloud(const PointCloud& scan, const std::vector<float>* offsets,
                                        const BodyVelocity& velocity, bool other_frame,
                                        OdometryResult* result) const {
  // Traversability needs several points per tri-grid node and walls a dense inlier band: the
  // keyframe cloud handed on is finer than the odometry's own grid. The registered cloud is
  // handed on as it is when it has that grid and the stamp's frame.
  const bool fine_grid = config_.keyframe_cloud_voxel_m > 0.0 &&
                         config_.keyframe_cloud_voxel_m != config_.preprocess.voxel_size_m;
  if (!fine_grid && !other_frame) return;
  PreprocessConfig fine = config_.preprocess;
  if (fine_grid) fine.voxel_size_m = config_.keyframe_cloud_voxel_m;
  fine.max_points = 0;  // walls and terrain want the dense cloud: the budget is the odometry's
  // Voxelised first, deskewed after (as the registered cloud): a dense scan's 65k returns cost
  // their few thousand voxels' transforms, each centroid moved with its returns' mean time.
  const bool timed = usableTimes(scan, offsets);
  std::vector<float> times;
  const PointCloud reduced =
      preprocess(scan, fine, nullptr, timed ? offsets : nullptr, timed ? &times : nullptr);
  bool deskewed = false;
  result->keyframe_cloud.reset(
      new PointCloud(compensate(reduced, timed ? &times : nullptr, velocity, &deskewed)));
}

}  // namespace tacs
