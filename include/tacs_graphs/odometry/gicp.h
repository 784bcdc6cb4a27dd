// Generalized-ICP (Segal et al., RSS 2009), the scan matcher of the odometry (paper Sec. III-A).
// Each point carries a covariance from its k nearest neighbours, regularised to a plane
// (eigenvalues -> 1, 1, 1e-3), so a pair of points is scored by a plane-to-plane distance.
// A prepared cloud (points, covariances, KD-tree) is immutable and shared, so the target of
// scan-to-map tracking is prepared once and aligned against many times.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "tacs_graphs/common/types.h"

namespace tacs {

struct GicpConfig {
  int k_neighbors = 10;                        // points per covariance (the point included)
  double max_correspondence_distance_m = 1.0;  // [m] farther pairs are not correspondences
  int max_iterations = 30;                     // Levenberg-Marquardt iterations
  double translation_eps_m = 1e-3;             // [m] converged when the step is below both
  double rotation_eps_deg = 0.05;              // [deg]
  int num_threads = 2;                         // OpenMP threads; 0 = OpenMP default
  // Geman-McClure kernel on each pair's Mahalanobis distance: two planes this far apart weigh a
  // quarter of an exact pair, 3x as far 1 %. Structure one cloud holds and the other lacks (a
  // surface first seen through a doorway) then pairs with a surface near it without pulling the
  // pose. 0: plain least squares.
  double robust_plane_distance_m = 0.0;  // [m]
  // With source point times (Gicp::setSourceTimes) the sweep's own motion is estimated too, with
  // a Gaussian prior of these widths on the correction to the velocity the sweep was deskewed
  // with: it holds the directions the scene leaves unobserved (a corridor's axis).
  double sweep_velocity_sigma_mps = 0.5;   // [m/s]
  double sweep_velocity_sigma_dps = 30.0;  // [deg/s]

  template <class V>
  void visit(V& v) {
    v("k_neighbors", k_neighbors);
    v("max_correspondence_distance_m", max_correspondence_distance_m);
    v("max_iterations", max_iterations);
    v("translation_eps_m", translation_eps_m);
    v("rotation_eps_deg", rotation_eps_deg);
    v("num_threads", num_threads);
    v("robust_plane_distance_m", robust_plane_distance_m);
    v("sweep_velocity_sigma_mps", sweep_velocity_sigma_mps);
    v("sweep_velocity_sigma_dps", sweep_velocity_sigma_dps);
  }
  void validate() const;
};

/// Variance along the normal of a plane-regularised covariance (the in-plane ones are 1).
inline constexpr double kGicpPlaneVariance = 1e-3;

/// Points with plane-regularised covariances and a KD-tree over them. Thread-safe to query.
class GicpCloud {
 public:
  using ConstPtr = std::shared_ptr<const GicpCloud>;

  /// Builds the KD-tree and the covariances (k nearest neighbours, num_threads as in GicpConfig).
  static ConstPtr build(const PointCloud& cloud, int k_neighbors, int num_threads);
  static ConstPtr build(std::vector<Eigen::Vector3d> points, int k_neighbors, int num_threads);
  /// Uses the given covariances (e.g. transformed ones of an earlier cloud); builds only the tree.
  static ConstPtr fromParts(std::vector<Eigen::Vector3d> points,
                            std::vector<Eigen::Matrix3d> covariances);

  ~GicpCloud();
  size_t size() const { return points_.size(); }
  bool empty() const { return points_.empty(); }
  const std::vector<Eigen::Vector3d>& points() const { return points_; }
  const std::vector<Eigen::Matrix3d>& covariances() const { return covariances_; }

  /// Index of the nearest point closer than sqrt(max_dist_sq), or -1; its squared distance.
  /// A hint (a likely answer, e.g. the last iteration's) shrinks the search radius; the result
  /// is the exact nearest point either way.
  int64_t nearest(const Eigen::Vector3d& query, double max_dist_sq, double* dist_sq,
                  int64_t hint = -1) const;
  /// Up to k nearest points (fewer when the cloud is smaller), closest first.
  void knn(const Eigen::Vector3d& query, int k, std::vector<uint32_t>* indices,
           std::vector<double>* dist_sq) const;

 private:
  struct Index;
  GicpCloud() = default;
  void buildIndex();

  std::vector<Eigen::Vector3d> points_;
  std::vector<Eigen::Matrix3d> covariances_;
  std::unique_ptr<Index> index_;
};

/// Covariance of a point's neighbourhood with eigenvalues replaced by (1, 1, 1e-3): a unit disc
/// in the local plane. Fewer than 3 neighbours give the identity (no known structure).
Eigen::Matrix3d planeRegularizedCovariance(const std::vector<Eigen::Vector3d>& points,
                                           const std::vector<uint32_t>& neighbours);
/// The same disc for a given (scatter or averaged) covariance: its smallest eigenvector is the
/// plane's normal.
Eigen::Matrix3d planeRegularized(const Eigen::Matrix3d& cov);

/// One cloud from several, each moved by its pose, on a voxel grid: each voxel's point is the
/// centroid of the points in it and its covariance the plane-regularised mean of theirs, turned
/// with their poses. No neighbour search: only the KD-tree is built, so a local map of many
/// keyframes is merged at the cost of a pass over their points (VGICP's voxel covariances,
/// Koide et al., ICRA 2021).
GicpCloud::ConstPtr mergeGicpClouds(
    const std::vector<std::pair<Pose3, GicpCloud::ConstPtr>>& clouds, double voxel_m,
    int num_threads);

struct GicpResult {
  bool converged = false;  // the last step was below the eps thresholds
  int iterations = 0;
  Pose3 T_target_source = Pose3::Identity();
  double fitness = 0.0;       // [m^2] mean squared distance of the inlier pairs
  double inlier_ratio = 0.0;  // share of source points with a correspondence
  size_t inliers = 0;
  /// Gauss-Newton Hessian of the GICP cost at the result: the information of T_target_source
  /// for a perturbation on the right (source frame), order x y z rx ry rz. Its scale follows
  /// the unit-less plane covariances, so consumers should scale it.
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
  /// With source point times: the twist (linear m/s, angular rad/s, in the source frame) by which
  /// the source still moved within its sweep, so a point measured t seconds after the source
  /// frame's time lies at T_target_source * exp(t * sweep_velocity) * p (a continuous-time
  /// registration, as in CT-ICP). Zero without times.
  Eigen::Matrix<double, 6, 1> sweep_velocity = Eigen::Matrix<double, 6, 1>::Zero();
  double time_ms = 0.0;
};

class Gicp {
 public:
  using Vector6 = Eigen::Matrix<double, 6, 1>;

  explicit Gicp(const GicpConfig& config = GicpConfig());

  void setTarget(const PointCloud& cloud);  // builds the KD-tree and covariances once
  void setTarget(GicpCloud::ConstPtr target);
  void setSource(const PointCloud& cloud);
  void setSource(GicpCloud::ConstPtr source);
  /// Seconds after the source frame's time at which each source point was measured (one per
  /// source point, after setSource): align() then also estimates the sweep's motion
  /// (GicpResult::sweep_velocity). Empty, or of another size: the source is one rigid cloud.
  void setSourceTimes(std::vector<double> offsets_s);
  const GicpCloud::ConstPtr& target() const { return target_; }
  const GicpCloud::ConstPtr& source() const { return source_; }
  const GicpConfig& config() const { return config_; }

  /// Aligns source to target from the initial guess of T_target_source. Without a target or
  /// source, or with no correspondence, returns converged = false and the guess.
  GicpResult align(const Pose3& initial_guess) const;

  /// Fitness, inliers and information of a given T_target_source, without optimising.
  GicpResult evaluate(const Pose3& T_target_source) const;
  /// evaluate()'s inlier_ratio alone: the share of source points with a target point within
  /// max_correspondence_distance_m, without building the Hessian (a fit test).
  double inlierRatio(const Pose3& T_target_source) const;

 private:
  struct Linearization;
  /// At pose T and sweep velocity `sweep` (ignored without source times). `previous`: the last
  /// linearisation (or null); its pairs seed the nearest-point searches.
  Linearization linearize(const Pose3& T, const Vector6& sweep,
                          const Linearization* previous) const;
  /// The source points moved by `sweep` over their times (the points themselves without times).
  std::vector<Eigen::Vector3d> sweptSource(const Vector6& sweep) const;
  void fillScores(const Linearization& lin, GicpResult* result) const;
  /// Information of the prior on the sweep velocity (diagonal, linear then angular).
  Eigen::Matrix<double, 6, 6> sweepPrior() const;
  /// Squared scale of the robust kernel in Mahalanobis units; 0 when it is off.
  double kernelC2() const;

  GicpConfig config_;
  GicpCloud::ConstPtr target_;
  GicpCloud::ConstPtr source_;
  std::vector<double> source_times_;
};

}  // namespace tacs
