// Scan-to-local-map GICP odometry (paper Sec. III-A): each scan is aligned to a map made of the
// most recent keyframes, from a constant-velocity guess; keyframes are taken by travelled
// distance and rotation and carry the downsampled scan for the rest of the pipeline.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tacs_graphs/common/types.h"
#include "tacs_graphs/odometry/carried_voxel_map.h"
#include "tacs_graphs/odometry/deskew.h"
#include "tacs_graphs/odometry/floor_level.h"
#include "tacs_graphs/odometry/gicp.h"
#include "tacs_graphs/odometry/point_times.h"
#include "tacs_graphs/odometry/preprocess.h"

namespace tacs {

struct OdometryConfig {
  PreprocessConfig preprocess;
  GicpConfig gicp;
  // Where the per-point time of a scan is read from (PointCloud2 field, unit, origin).
  PointTimeConfig point_times;
  // Motion compensation from the per-point time: each scan is deskewed with the constant-velocity
  // guess before registration; with deskew_refine, once more with the registered motion when it
  // differs from the guess, followed by a short refinement.
  bool deskew = true;
  bool deskew_refine = true;
  // With point times, the registration also estimates the sweep's own motion (continuous time,
  // GicpResult::sweep_velocity) and deskews the scan again with it. Off by default: on the
  // distorted worlds it helps some and costs others (docs/DESIGN.md, "A scan's way").
  bool sweep_motion = false;
  // Register each deskewed scan at its sweep's middle, not at its stamp, and carry the pose back
  // to the stamp with the step's velocity. An error of the deskew velocity then bends the cloud
  // about its middle instead of shifting it as a whole: the pose no longer takes up the error,
  // and the next velocity (a difference of two poses) does not feed it back.
  bool deskew_to_mid_sweep = true;
  double keyframe_distance_m = 0.5;  // [m] new keyframe after this translation from the last one
  double keyframe_angle_deg = 15.0;  // [deg] ... or after this rotation
  int local_map_keyframes = 10;      // keyframes in the sliding-window local map
  double local_map_voxel_m = 0.2;    // [m] voxel size of the merged local map
  // Where the local map's covariances come from: "neighbours" searches them anew on the merged
  // map (several viewpoints give better planes than the sparse rings of one VLP-16 scan);
  // "carried" averages the keyframes' own per voxel (mergeGicpClouds), no search: a dense
  // scan's planes are already good, and a keyframe at every scan (a 1 Hz hand-held recording)
  // then costs a pass over the window's points, not a neighbour search over the map.
  std::string local_map_covariances = "neighbours";
  int min_scan_points = 100;    // fewer points after preprocessing: scan rejected
  double max_time_gap_s = 0.5;  // [s] longer gaps reset the constant-velocity guess
  // Without a motion prior (start, time gap, rejected scan) a first coarse alignment uses this
  // wider gating [m], so a jump of up to about this size is recovered.
  double recovery_correspondence_distance_m = 2.5;
  // [m] gate of a second alignment from the first one's result (0, or not below
  // gicp.max_correspondence_distance_m: off). Under the wide gate, points of structure the local
  // map lacks pair with other surfaces up to a metre away and can drag a scan along a corridor;
  // the narrow pass keeps only the close pairs.
  double refine_correspondence_distance_m = 0.5;
  // [m] robust kernel of that second alignment (GicpConfig::robust_plane_distance_m; 0: least
  // squares). The narrow gate still pairs a surface the map lacks with one up to 0.5 m away
  // (a wall behind a cabinet first seen, the far side of a thin wall); under least squares such
  // pairs shifted scans by 2-4 cm along corridors for a few scans until the next keyframe.
  double refine_robust_plane_distance_m = 0.03;
  // With the narrow-gate refinement on, the first (wide-gate) alignment only has to bring the
  // scan into the refinement's basin: it runs on an evenly strided subset of at most this many
  // of the scan's points, the refinement on all of them (0: all points in both). On the 13 worlds
  // the same walls, rooms and loops and the same keyframe ATE; large_hall 53 -> 75 scans/s.
  int wide_gate_max_points = 1500;
  double min_inlier_ratio = 0.3;  // registrations with fewer inliers are rejected
  // A registration that moves the constant-velocity guess by more than these limits, or that
  // matches fewer than recovery_min_fit of the scan within fit_distance_m, is retried from
  // several yaw hypotheses (recovery); the limits widen with the recent motion-model error
  // (3 sigma), up to max_adaptive_correction_m / _deg, so a hand-held sensor's fast turns are
  // followed while a wheeled robot's keep the tight default.
  double max_correction_m = 1.0;              // [m] floor of the translation limit
  double max_correction_deg = 30.0;           // [deg] floor of the rotation limit
  double max_adaptive_correction_m = 3.0;     // [m] ceiling of the translation limit
  double max_adaptive_correction_deg = 90.0;  // [deg] ceiling of the rotation limit
  double fit_distance_m = 0.3;    // [m] a scan point within this of the map counts as fitting
  double recovery_min_fit = 0.5;  // share of fitting points below which the scan is re-aligned
  // ... or below this share of the recent scans' fit (running mean)
  double recovery_relative_fit = 0.85;
  // A recovery replaces a registration within the limits only when it fits this much larger a
  // share of the scan (one outside the limits is replaced by any better fit) [-].
  double recovery_min_gain = 0.05;
  // ... and only by a hypothesis the sensor's carrier could reach: one turned from the
  // constant-velocity guess by no more than this angular acceleration turns it within the scan
  // interval dt (0.5 a dt^2: 18 deg at 10 Hz, no bound at 1 Hz) [deg/s^2].
  double recovery_max_angular_accel_dps2 = 3600.0;
  // Yaw offsets [deg] tried from the guess when recovering (about the base z axis), each
  // aligned coarse to fine and scored by its share of fitting points.
  std::vector<double> recovery_yaw_deg = {0.0, 30.0, -30.0, 60.0, -60.0, 90.0, -90.0, 180.0};
  double recovery_voxel_m = 0.6;  // [m] source grid of the coarse hypothesis alignments
  // Iterations of each coarse hypothesis alignment: it only has to reach its basin, the fine pass
  // settles it (BALM hall: 30 -> 10 saves a quarter of a recovery, same poses).
  int recovery_coarse_iterations = 10;
  // The first scan's pose is levelled on the floor it sees (a plane at least 0.3 m below the
  // base, tilted at most level_max_tilt_deg), so a tilted hand-held sensor starts a level map. A
  // base frame on the floor (a wheeled robot's base_link) sees no floor below it: pose kept.
  bool level_from_floor = true;
  double level_max_tilt_deg = 40.0;  // [deg]
  // [m] voxel of the keyframe cloud handed to traversability and walls (0: the odometry's own
  // preprocess.voxel_size_m grid)
  double keyframe_cloud_voxel_m = 0.1;

  template <class V>
  void visit(V& v) {
    v("preprocess", preprocess);
    v("gicp", gicp);
    v("point_times", point_times);
    v("deskew", deskew);
    v("deskew_refine", deskew_refine);
    v("sweep_motion", sweep_motion);
    v("deskew_to_mid_sweep", deskew_to_mid_sweep);
    v("keyframe_distance_m", keyframe_distance_m);
    v("keyframe_angle_deg", keyframe_angle_deg);
    v("local_map_keyframes", local_map_keyframes);
    v("local_map_voxel_m", local_map_voxel_m);
    v("local_map_covariances", local_map_covariances);
    v("min_scan_points", min_scan_points);
    v("max_time_gap_s", max_time_gap_s);
    v("recovery_correspondence_distance_m", recovery_correspondence_distance_m);
    v("refine_correspondence_distance_m", refine_correspondence_distance_m);
    v("refine_robust_plane_distance_m", refine_robust_plane_distance_m);
    v("wide_gate_max_points", wide_gate_max_points);
    v("min_inlier_ratio", min_inlier_ratio);
    v("max_correction_m", max_correction_m);
    v("max_correction_deg", max_correction_deg);
    v("max_adaptive_correction_m", max_adaptive_correction_m);
    v("max_adaptive_correction_deg", max_adaptive_correction_deg);
    v("fit_distance_m", fit_distance_m);
    v("recovery_min_fit", recovery_min_fit);
    v("recovery_relative_fit", recovery_relative_fit);
    v("recovery_min_gain", recovery_min_gain);
    v("recovery_max_angular_accel_dps2", recovery_max_angular_accel_dps2);
    v("recovery_yaw_deg", recovery_yaw_deg);
    v("recovery_voxel_m", recovery_voxel_m);
    v("recovery_coarse_iterations", recovery_coarse_iterations);
    v("level_from_floor", level_from_floor);
    v("level_max_tilt_deg", level_max_tilt_deg);
    v("keyframe_cloud_voxel_m", keyframe_cloud_voxel_m);
  }
  void validate() const;
};

struct OdometryResult {
  bool ok = false;
  std::string error;  // why ok is false, e.g. "empty scan after preprocessing (...)"
  double stamp = 0.0;
  Pose3 T_odom_base = Pose3::Identity();  // the scan's pose; the last good pose when !ok
  bool is_keyframe = false;
  uint32_t keyframe_id = 0;
  /// Scan in the base frame at keyframe_cloud_voxel_m (keyframes only).
  PointCloud::Ptr keyframe_cloud;
  /// Information of the motion since the previous keyframe (keyframes only; zero for the first),
  /// order x y z rx ry rz, perturbation in this keyframe's frame. GICP Hessian scale.
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
  bool motion_prior_reset = false;  // the guess was the last pose (no velocity known)
  bool deskewed = false;            // the scan was motion-compensated from its point times
  bool recovered = false;           // the guess's alignment failed; a yaw hypothesis won
  double fit = 0.0;                 // share of scan points within fit_distance_m of the map
  std::optional<FloorPlane> floor;  // first scan: the floor that levelled the odom frame
  GicpResult registration;
  PreprocessStats preprocess;
  double time_ms = 0.0;
};

/// A scan made ready for registration by what depends on no earlier scan
/// (LidarOdometry::prepare): the instant it is registered at, its voxelised points with their
/// times, and their covariances as measured (process() carries them into the deskewed scan).
/// Made on any thread, ahead of LidarOdometry::process.
struct PreparedScan {
  double stamp = 0.0;
  double ref_s = 0.0;  // the instant registered, relative to the stamp (the sweep's middle), or 0
  std::shared_ptr<const PointCloud> raw;  // the scan as given: keyframe clouds are made from it
  std::shared_ptr<const std::vector<float>> raw_offsets;  // its point times (stamp-relative)
  std::vector<float> mid_offsets;  // the point times relative to the instant, when ref_s != 0
  bool has_times = false;          // the scan is deskewed (OdometryConfig::deskew, times given)
  PointCloud reduced;              // preprocessed
  std::vector<float> times;        // of the reduced points, when has_times
  PreprocessStats stats;
  GicpCloud::ConstPtr gicp;  // reduced with covariances (as measured: before any deskew)
  double time_ms = 0.0;
  /// The point times of the raw scan the registration uses (relative to the instant).
  const std::vector<float>* offsets() const {
    return ref_s != 0.0 ? &mid_offsets : raw_offsets.get();
  }
};

class LidarOdometry {
 public:
  explicit LidarOdometry(const OdometryConfig& config);

  /// `scan` is in the base frame (the caller applies the sensor extrinsic). Never throws on bad
  /// data: empty, all-invalid, too sparse or unregistrable scans and non-increasing stamps give
  /// ok = false with a reason and leave the state as it was; a gap longer than max_time_gap_s
  /// resets the constant-velocity guess instead of extrapolating it.
  ///
  /// `point_offsets_s` (optional, one per point of `scan`): the time of each point relative to
  /// `stamp` (resolvePointTimes); with them the scan is deskewed to `stamp` before anything
  /// else sees it, and the keyframe cloud is the deskewed one.
  OdometryResult process(double stamp, const PointCloud& scan,
                         const std::vector<float>* point_offsets_s = nullptr);

  /// process() in two steps: prepare() reads only the configuration, so a scan can be prepared
  /// on another thread while earlier ones are registered; process(prepared) then gives what
  /// process() gives. `scan` and `point_offsets_s` are kept (shared) for the keyframe cloud.
  PreparedScan prepare(double stamp, std::shared_ptr<const PointCloud> scan,
                       std::shared_ptr<const std::vector<float>> point_offsets_s) const;
  OdometryResult process(const PreparedScan& scan);

  const OdometryConfig& config() const { return config_; }
  /// Pose of the last accepted scan.
  const Pose3& pose() const { return stamp_pose_; }
  /// The current local map (odom frame), null before the first scan.
  const GicpCloud::ConstPtr& localMap() const { return local_map_; }
  size_t numKeyframes() const { return next_keyframe_id_; }

 private:
  struct Keyframe {
    uint32_t id = 0;
    Pose3 T_odom_base = Pose3::Identity();
    PointCloud::Ptr cloud;     // base frame
    GicpCloud::ConstPtr gicp;  // base frame, with covariances
  };

  // One step of process(), each named for what it does.
  /// The first scan: defines the odom frame (levelled on the floor when level_from_floor).
  void startOn(double stamp, const PointCloud::Ptr& cloud, const GicpCloud::ConstPtr& scan_gicp,
               OdometryResult* result);
  Pose3 predict(double stamp, bool* reset) const;
  /// True when the scan is to be deskewed: deskew on and one time per point.
  bool usableTimes(const PointCloud& scan, const std::vector<float>* offsets) const {
    return config_.deskew && offsets && offsets->size() == scan.size();
  }
  /// The scan deskewed with `velocity` when it has point times, else the scan itself.
  PointCloud compensate(const PointCloud& scan, const std::vector<float>* offsets,
                        const BodyVelocity& velocity, bool* deskewed) const;
  /// Aligns the scan to the local map from the guess, coarse to fine; falls back to the yaw
  /// hypotheses when the result does not fit or moved the guess beyond the adaptive limits.
  /// `sweep_times`: the scan's point times when the sweep's motion is estimated, else null.
  /// `dt`: seconds since the last registered scan.
  GicpResult registerScan(const GicpCloud::ConstPtr& scan, const PointCloud& cloud,
                          const std::vector<float>* sweep_times, const Pose3& guess, bool reset,
                          double dt, OdometryResult* result) const;
  GicpResult align(const GicpCloud::ConstPtr& scan, double gate_m, const Pose3& from,
                   double robust_m, const std::vector<float>* sweep_times = nullptr) const {
    return alignTo(local_map_, scan, gate_m, from, robust_m, config_.gicp.max_iterations,
                   sweep_times);
  }
  GicpResult alignTo(const GicpCloud::ConstPtr& target, const GicpCloud::ConstPtr& scan,
                     double gate_m, const Pose3& from, double robust_m, int max_iterations,
                     const std::vector<float>* sweep_times = nullptr) const;
  /// The scan, or its strided subset of at most wide_gate_max_points points (and their times in
  /// *subset_times) when the refinement follows.
  GicpCloud::ConstPtr wideGateSource(const GicpCloud::ConstPtr& scan,
                                     const std::vector<float>* sweep_times,
                                     std::vector<float>* subset_times) const;
  /// Re-aligns on refine_correspondence_distance_m when it is narrower than the gate.
  void refineOnNarrowGate(const GicpCloud::ConstPtr& scan, const std::vector<float>* sweep_times,
                          GicpResult* registration) const;
  /// Why the registration is not taken (too few inliers, beyond the adaptive limits), or "".
  std::string rejection(const Pose3& guess, bool reset, const OdometryResult& result) const;
  double fitOf(const GicpCloud::ConstPtr& scan, const Pose3& T) const;
  bool withinLimits(const Pose3& guess, const Pose3& T) const;
  /// T turns away from the guess by no more than recovery_max_angular_accel_dps2 turns in dt.
  bool reachableIn(double dt, const Pose3& guess, const Pose3& T) const;
  /// The best of the yaw hypotheses; their fine passes run on `fine_source` (the scan or the
  /// wide gate's subset of it), their fit is scored on the whole scan.
  GicpResult recoverFromHypotheses(const PointCloud& cloud, const GicpCloud::ConstPtr& scan,
                                   const GicpCloud::ConstPtr& fine_source,
                                   const Pose3& guess) const;
  void updateMotionModel(double stamp, const Pose3& guess, const Pose3& pose, bool reset);
  void updateRecentFit(double fit);
  bool isKeyframe(const Pose3& T_odom_base) const;
  void addKeyframe(OdometryResult* result, const GicpCloud::ConstPtr& scan_gicp,
                   const PointCloud::Ptr& cloud);
  void rebuildLocalMap();
  /// Why a scan of `points` preprocessed points is not registered (too few, with the counts of
  /// what preprocessing dropped), or "".
  std::string tooFewPoints(size_t points, const PreprocessStats& stats) const;
  /// Deskews the preprocessed scan again with the registered motion (deskew_refine) into `cloud`
  /// and `scan_gicp` (covariances carried); returns that motion.
  BodyVelocity deskewWithRegisteredMotion(double t, const PointCloud& reduced,
                                          const std::vector<float>& times,
                                          const BodyVelocity& velocity, bool timed,
                                          OdometryResult* result, PointCloud::Ptr* cloud,
                                          GicpCloud::ConstPtr* scan_gicp) const;
  GicpCloud::ConstPtr coarseMap() const;
  /// The keyframe cloud handed on, from the raw scan deskewed with `velocity` over `offsets`
  /// (none: as measured), when it differs from the registered cloud: a finer grid, or
  /// `other_frame` (the registered cloud is not in the stamp's frame).
  void attachKeyframeCloud(const PointCloud& scan, const std::vector<float>* offsets,
                           const BodyVelocity& velocity, bool other_frame,
                           OdometryResult* result) const;
  /// The middle of the sweep relative to the stamp [s] when the scan is deskewed and
  /// deskew_to_mid_sweep is on (`shifted`: the point times relative to it), else 0.
  double sweepReference(const PointCloud& scan, const std::vector<float>* offsets,
                        std::vector<float>* shifted) const;

  OdometryConfig config_;
  bool initialized_ = false;
  // The last accepted scan: its registered instant and pose (the sweep's middle with
  // deskew_to_mid_sweep), its stamp and the pose at the stamp.
  double last_stamp_ = 0.0;
  Pose3 last_pose_ = Pose3::Identity();
  double last_scan_stamp_ = 0.0;
  Pose3 stamp_pose_ = Pose3::Identity();
  // The twist of the last accepted step (the constant-velocity motion model).
  bool has_velocity_ = false;
  BodyVelocity velocity_;
  // Running RMS of the constant-velocity guess's error (translation [m], rotation [rad]): the
  // adaptive correction limits are 3x these.
  double model_error_m_ = 0.0;
  double model_error_rad_ = 0.0;
  double scan_interval_s_ = 0.0;  // running typical interval between scans
  double recent_fit_ = 0.0;       // running mean of the accepted scans' fit
  std::deque<Keyframe> window_;
  GicpCloud::ConstPtr local_map_;
  // The window's voxels with carried covariances (local_map_covariances: carried).
  std::unique_ptr<CarriedVoxelMap> carried_map_;
  // The local map on recovery_voxel_m's grid (coarseMap()), made when first needed after each
  // keyframe.
  mutable GicpCloud::ConstPtr coarse_map_;
  uint32_t next_keyframe_id_ = 0;
};

}  // namespace tacs
