#include "tacs_graphs/odometry/gicp.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "tacs_graphs/common/config.h"
#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/odometry/deskew.h"
#include "tacs_graphs/odometry/parallel.h"

namespace tacs {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

void GicpConfig::validate() const {
  requireConfig(k_neighbors >= 3, "odometry.gicp.k_neighbors",
                "must be >= 3 (a plane needs 3 points)");
  requireConfig(max_correspondence_distance_m > 0.0, "odometry.gicp.max_correspondence_distance_m",
                "must be > 0");
  requireConfig(max_iterations >= 1, "odometry.gicp.max_iterations", "must be >= 1");
  requireConfig(translation_eps_m > 0.0, "odometry.gicp.translation_eps_m", "must be > 0");
  requireConfig(rotation_eps_deg > 0.0, "odometry.gicp.rotation_eps_deg", "must be > 0");
  requireConfig(num_threads >= 0, "odometry.gicp.num_threads", "must be >= 0 (0 = OpenMP default)");
  requireConfig(robust_plane_distance_m >= 0.0, "odometry.gicp.robust_plane_distance_m",
                "must be >= 0 (0 = off)");
  requireConfig(sweep_velocity_sigma_mps > 0.0, "odometry.gicp.sweep_velocity_sigma_mps",
                "must be > 0");
  requireConfig(sweep_velocity_sigma_dps > 0.0, "odometry.gicp.sweep_velocity_sigma_dps",
                "must be > 0");
}

namespace {

// T * Exp(delta) with delta = (v, w) on the right: t += R v, R = R Exp(w).
Pose3 retract(const Pose3& T, const Vector6d& delta) {
  Pose3 out = T;
  out.translation() += T.linear() * delta.head<3>();
  const Eigen::Vector3d w = delta.tail<3>();
  const double angle = w.norm();
  if (angle > 0.0) {
    Eigen::Quaterniond q(T.linear() * Eigen::AngleAxisd(angle, w / angle).toRotationMatrix());
    out.linear() = q.normalized().toRotationMatrix();
  }
  return out;
}

// A source point's correspondence: target index (or -1) and the pair's inverse covariance.
struct Correspondence {
  int64_t target = -1;
  Eigen::Matrix3d mahalanobis;
};

// Geman-McClure: rho(e) = c2 e / (c2 + e) of the squared Mahalanobis distance e, whose
// derivative (c2 / (c2 + e))^2 weighs the pair in the normal equations (IRLS). c2 <= 0: rho = e.
double robustCost(double e, double c2) { return c2 > 0.0 ? c2 * e / (c2 + e) : e; }
double robustWeight(double e, double c2) {
  if (c2 <= 0.0) return 1.0;
  const double s = c2 / (c2 + e);
  return s * s;
}

}  // namespace

struct Gicp::Linearization {
  Matrix6d H = Matrix6d::Zero();
  Vector6d g = Vector6d::Zero();
  // With source times, the blocks of the sweep velocity: a point measured t s into the sweep
  // has the Jacobian t * J, so its blocks are t * J^T M J (pose x sweep), t^2 * J^T M J and
  // t * J^T M r.
  Matrix6d H_pose_sweep = Matrix6d::Zero();
  Matrix6d H_sweep = Matrix6d::Zero();
  Vector6d g_sweep = Vector6d::Zero();
  double cost = 0.0;     // sum of squared Mahalanobis distances
  double sq_dist = 0.0;  // sum of squared Euclidean distances
  size_t inliers = 0;
  std::vector<Correspondence> pairs;  // filled by linearize(), not by +=

  Linearization& operator+=(const Linearization& o) {
    H += o.H;
    g += o.g;
    H_pose_sweep += o.H_pose_sweep;
    H_sweep += o.H_sweep;
    g_sweep += o.g_sweep;
    cost += o.cost;
    sq_dist += o.sq_dist;
    inliers += o.inliers;
    return *this;
  }
};

Gicp::Gicp(const GicpConfig& config) : config_(config) {}

void Gicp::setTarget(const PointCloud& cloud) {
  target_ = GicpCloud::build(cloud, config_.k_neighbors, config_.num_threads);
}
void Gicp::setTarget(GicpCloud::ConstPtr target) { target_ = std::move(target); }
void Gicp::setSource(const PointCloud& cloud) {
  source_ = GicpCloud::build(cloud, config_.k_neighbors, config_.num_threads);
}
void Gicp::setSource(GicpCloud::ConstPtr source) { source_ = std::move(source); }
void Gicp::setSourceTimes(std::vector<double> offsets_s) { source_times_ = std::move(offsets_s); }

std::vector<Eigen::Vector3d> Gicp::sweptSource(const Vector6& sweep) const {
  std::vector<Eigen::Vector3d> out = source_->points();
  if (source_times_.size() != out.size() || out.empty()) return out;
  const auto [lo, hi] = std::minmax_element(source_times_.begin(), source_times_.end());
  BodyVelocity velocity;
  velocity.linear = sweep.head<3>();
  velocity.angular = sweep.tail<3>();
  const MotionGrid motion(velocity, *lo, *hi);
  for (size_t i = 0; i < out.size(); ++i)
    out[i] = motion.pose(motion.cell(source_times_[i])) * out[i];
  return out;
}

Gicp::Linearization Gicp::linearize(const Pose3& T, const Vector6& sweep,
                                    const Linearization* previous) const {
  const bool timed = source_times_.size() == source_->size();
  const std::vector<Eigen::Vector3d> swept =
      timed ? sweptSource(sweep) : std::vector<Eigen::Vector3d>();
  const auto& src = timed ? swept : source_->points();
  const auto& src_cov = source_->covariances();
  const auto& tgt = target_->points();
  const auto& tgt_cov = target_->covariances();
  const Eigen::Matrix3d R = T.linear();
  const double max_sq =
      config_.max_correspondence_distance_m * config_.max_correspondence_distance_m;
  const double kernel_c2 = kernelC2();
  std::vector<Correspondence> pairs(src.size());
  // Between iterations a point's nearest target rarely moves far: the last one bounds the search.
  const std::vector<Correspondence>* hints =
      previous && previous->pairs.size() == src.size() ? &previous->pairs : nullptr;
  Linearization lin = parallelReduce<Linearization>(
      static_cast<int64_t>(src.size()), config_.num_threads, [&](int64_t i, Linearization& acc) {
        const Eigen::Vector3d p = T * src[i];
        double dist_sq = 0.0;
        const int64_t j = target_->nearest(p, max_sq, &dist_sq, hints ? (*hints)[i].target : -1);
        Correspondence& c = pairs[i];
        c.target = j;
        if (j < 0) return;
        // Combined covariance of the pair (GICP): C_target + R C_source R^T.
        c.mahalanobis = (tgt_cov[j] + R * src_cov[i] * R.transpose()).inverse();
        const Eigen::Vector3d r = tgt[j] - p;
        Eigen::Matrix<double, 3, 6> J;  // d r / d delta for T * Exp(delta)
        J.leftCols<3>() = -R;
        J.rightCols<3>() = R * skew(src[i]);
        const double e = r.dot(c.mahalanobis * r);
        const Eigen::Matrix<double, 6, 3> JtM =
            robustWeight(e, kernel_c2) * J.transpose() * c.mahalanobis;
        if (timed) {
          const Matrix6d JtMJ = JtM * J;
          const Vector6d JtMr = JtM * r;
          const double t = source_times_[i];
          acc.H += JtMJ;
          acc.g += JtMr;
          acc.H_pose_sweep += t * JtMJ;
          acc.H_sweep += (t * t) * JtMJ;
          acc.g_sweep += t * JtMr;
        } else {
          acc.H.noalias() += JtM * J;
          acc.g.noalias() += JtM * r;
        }
        acc.cost += robustCost(e, kernel_c2);
        acc.sq_dist += dist_sq;
        ++acc.inliers;
      });
  lin.pairs = std::move(pairs);
  if (timed) {  // the prior on the sweep velocity (GicpConfig::sweep_velocity_sigma_*)
    const Matrix6d prior = sweepPrior();
    lin.H_sweep += prior;
    lin.g_sweep += prior * sweep;
    lin.cost += sweep.dot(prior * sweep);
  }
  return lin;
}

void Gicp::fillScores(const Linearization& lin, GicpResult* result) const {
  result->inliers = lin.inliers;
  result->inlier_ratio = static_cast<double>(lin.inliers) / source_->size();
  result->fitness = lin.inliers ? lin.sq_dist / lin.inliers : 0.0;
  result->information = lin.H;
}

double Gicp::kernelC2() const {
  // Two parallel planes a distance d apart: squared Mahalanobis distance d^2 / (2 kFlat).
  const double d = config_.robust_plane_distance_m;
  return d * d / (2.0 * kGicpPlaneVariance);
}

GicpResult Gicp::evaluate(const Pose3& T_target_source) const {
  Stopwatch watch;
  GicpResult result;
  result.T_target_source = T_target_source;
  if (target_ && source_ && !target_->empty() && !source_->empty()) {
    fillScores(linearize(T_target_source, Vector6d::Zero(), nullptr), &result);
  }
  result.time_ms = watch.elapsedMs();
  return result;
}

double Gicp::inlierRatio(const Pose3& T_target_source) const {
  if (!target_ || !source_ || target_->empty() || source_->empty()) return 0.0;
  struct Count {
    size_t n = 0;
    Count& operator+=(const Count& o) {
      n += o.n;
      return *this;
    }
  };
  const auto& src = source_->points();
  const double max_sq =
      config_.max_correspondence_distance_m * config_.max_correspondence_distance_m;
  const Count found = parallelReduce<Count>(
      static_cast<int64_t>(src.size()), config_.num_threads, [&](int64_t i, Count& acc) {
        double dist_sq = 0.0;
        if (target_->nearest(T_target_source * src[i], max_sq, &dist_sq, -1) >= 0) ++acc.n;
      });
  return static_cast<double>(found.n) / src.size();
}

GicpResult Gicp::align(const Pose3& initial_guess) const {
  Stopwatch watch;
  GicpResult result;
  result.T_target_source = initial_guess;
  if (!target_ || !source_ || target_->empty() || source_->empty()) {
    result.time_ms = watch.elapsedMs();
    return result;
  }
  const bool timed = source_times_.size() == source_->size();
  const auto& tgt = target_->points();
  const double rot_eps = config_.rotation_eps_deg * M_PI / 180.0;
  const double kernel_c2 = kernelC2();
  const Matrix6d prior = sweepPrior();

  Pose3 T = initial_guess;
  Vector6d sweep = Vector6d::Zero();
  Linearization lin = linearize(T, sweep, nullptr);
  double lambda = -1.0;
  for (int iter = 0; iter < config_.max_iterations && lin.inliers >= 6; ++iter) {
    result.iterations = iter + 1;
    // Levenberg-Marquardt: damp until the cost (same pairs) decreases.
    if (lambda < 0.0) lambda = 1e-9 * lin.H.diagonal().maxCoeff();
    bool accepted = false;
    Vector6d delta = Vector6d::Zero(), delta_sweep = Vector6d::Zero();
    for (int attempt = 0; attempt < 10 && !accepted; ++attempt) {
      if (timed) {  // pose and sweep velocity together (12 unknowns)
        Eigen::Matrix<double, 12, 12> H;
        H << lin.H, lin.H_pose_sweep, lin.H_pose_sweep.transpose(), lin.H_sweep;
        H.diagonal().array() += lambda;
        Eigen::Matrix<double, 12, 1> g;
        g << lin.g, lin.g_sweep;
        const Eigen::Matrix<double, 12, 1> step = H.ldlt().solve(-g);
        delta = step.head<6>();
        delta_sweep = step.tail<6>();
      } else {
        delta = (lin.H + lambda * Matrix6d::Identity()).ldlt().solve(-lin.g);
      }
      const Pose3 candidate = retract(T, delta);
      const Vector6d candidate_sweep = sweep + delta_sweep;
      const std::vector<Eigen::Vector3d> swept =
          timed ? sweptSource(candidate_sweep) : std::vector<Eigen::Vector3d>();
      const auto& src = timed ? swept : source_->points();
      // Serial: one 3x3 product per pair is cheaper than waking a second thread.
      double trial_cost = timed ? candidate_sweep.dot(prior * candidate_sweep) : 0.0;
      for (size_t i = 0; i < src.size(); ++i) {
        const Correspondence& c = lin.pairs[i];
        if (c.target < 0) continue;
        const Eigen::Vector3d r = tgt[c.target] - candidate * src[i];
        trial_cost += robustCost(r.dot(c.mahalanobis * r), kernel_c2);
      }
      if (trial_cost <= lin.cost) {
        T = candidate;
        sweep = candidate_sweep;
        accepted = true;
        lambda *= 0.1;
      } else {
        lambda = std::max(lambda * 10.0, 1e-12);
      }
    }
    if (!accepted) {  // no step lowers the cost: at the minimum for these pairs
      result.converged = true;
      break;
    }
    lin = linearize(T, sweep, &lin);
    // The sweep's change is judged by what it moves the sweep's last point (0.1 s of a 10 Hz
    // LiDAR) against the same thresholds.
    if (delta.head<3>().norm() < config_.translation_eps_m && delta.tail<3>().norm() < rot_eps &&
        0.1 * delta_sweep.head<3>().norm() < config_.translation_eps_m &&
        0.1 * delta_sweep.tail<3>().norm() < rot_eps) {
      result.converged = true;
      break;
    }
  }
  result.T_target_source = T;
  result.sweep_velocity = sweep;
  fillScores(lin, &result);
  result.time_ms = watch.elapsedMs();
  return result;
}

Matrix6d Gicp::sweepPrior() const {
  // In the cost's units (squared Mahalanobis distances): a correction of one sigma costs 1.
  const double sigma_rad = config_.sweep_velocity_sigma_dps * M_PI / 180.0;
  Vector6d inv_var;
  const double sigma_m = config_.sweep_velocity_sigma_mps;
  inv_var << Eigen::Vector3d::Constant(1.0 / (sigma_m * sigma_m)),
      Eigen::Vector3d::Constant(1.0 / (sigma_rad * sigma_rad));
  return inv_var.asDiagonal();
}

}  // namespace tacs
