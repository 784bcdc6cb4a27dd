#include "tacs_graphs/eval/trajectory_metrics.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tacs {

std::vector<std::pair<size_t, size_t>> associateByTime(const Trajectory& estimate,
                                                       const Trajectory& ground_truth,
                                                       double max_dt) {
  std::vector<std::pair<size_t, size_t>> pairs;
  if (ground_truth.empty()) return pairs;
  size_t j = 0;
  for (size_t i = 0; i < estimate.size(); ++i) {
    const double t = estimate[i].stamp;
    while (j + 1 < ground_truth.size() && ground_truth[j + 1].stamp <= t) ++j;
    // Nearest of the neighbours j and j + 1.
    size_t best = j;
    if (j + 1 < ground_truth.size() &&
        std::abs(ground_truth[j + 1].stamp - t) < std::abs(ground_truth[j].stamp - t)) {
      best = j + 1;
    }
    if (std::abs(ground_truth[best].stamp - t) <= max_dt) pairs.emplace_back(i, best);
  }
  return pairs;
}

Pose3 alignRigid(const std::vector<Eigen::Vector3d>& src, const std::vector<Eigen::Vector3d>& dst) {
  Pose3 T = Pose3::Identity();
  if (src.empty() || src.size() != dst.size()) return T;
  Eigen::Vector3d mu_src = Eigen::Vector3d::Zero(), mu_dst = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < src.size(); ++i) {
    mu_src += src[i];
    mu_dst += dst[i];
  }
  mu_src /= src.size();
  mu_dst /= dst.size();
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < src.size(); ++i) cov += (dst[i] - mu_dst) * (src[i] - mu_src).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(cov, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0) S(2, 2) = -1;  // no reflection
  T.linear() = svd.matrixU() * S * svd.matrixV().transpose();
  T.translation() = mu_dst - T.linear() * mu_src;
  return T;
}

AteResult computeAte(const Trajectory& estimate, const Trajectory& ground_truth, double max_dt) {
  const auto pairs = associateByTime(estimate, ground_truth, max_dt);
  if (pairs.size() < 3) {
    throw std::invalid_argument("ATE: only " + std::to_string(pairs.size()) +
                                " poses associate in time (need 3)");
  }
  std::vector<Eigen::Vector3d> est, gt;
  for (const auto& [i, j] : pairs) {
    est.push_back(estimate[i].pose.translation());
    gt.push_back(ground_truth[j].pose.translation());
  }
  AteResult r;
  r.pairs = pairs.size();
  r.T_gt_estimate = alignRigid(est, gt);
  double sum_sq = 0.0;
  for (size_t k = 0; k < est.size(); ++k) {
    const double e = (r.T_gt_estimate * est[k] - gt[k]).norm();
    sum_sq += e * e;
    r.mean += e;
    r.max = std::max(r.max, e);
  }
  r.rmse = std::sqrt(sum_sq / est.size());
  r.mean /= est.size();
  return r;
}

DriftResult computeDrift(const Trajectory& estimate, const Trajectory& ground_truth,
                         double segment_length, double max_dt) {
  DriftResult r;
  const auto pairs = associateByTime(estimate, ground_truth, max_dt);
  if (pairs.size() < 2) return r;
  // Distance travelled along the ground truth up to each associated pose.
  std::vector<double> travelled(pairs.size(), 0.0);
  for (size_t k = 1; k < pairs.size(); ++k) {
    travelled[k] = travelled[k - 1] + (ground_truth[pairs[k].second].pose.translation() -
                                       ground_truth[pairs[k - 1].second].pose.translation())
                                          .norm();
  }
  double sum = 0.0;
  size_t end = 0;
  for (size_t start = 0; start < pairs.size(); ++start) {
    end = std::max(end, start);
    while (end < pairs.size() && travelled[end] - travelled[start] < segment_length) ++end;
    if (end == pairs.size()) break;
    const Pose3& e0 = estimate[pairs[start].first].pose;
    const Pose3& e1 = estimate[pairs[end].first].pose;
    const Pose3& g0 = ground_truth[pairs[start].second].pose;
    const Pose3& g1 = ground_truth[pairs[end].second].pose;
    const Eigen::Vector3d est_rel = (e0.inverse() * e1).translation();
    const Eigen::Vector3d gt_rel = (g0.inverse() * g1).translation();
    sum += (est_rel - gt_rel).norm();
    ++r.segments;
  }
  if (r.segments > 0) {
    r.mean_error_m = sum / r.segments;
    r.percent = 100.0 * r.mean_error_m / segment_length;
  }
  return r;
}

double pathLength(const Trajectory& trajectory) {
  double length = 0.0;
  for (size_t i = 1; i < trajectory.size(); ++i) {
    length += (trajectory[i].pose.translation() - trajectory[i - 1].pose.translation()).norm();
  }
  return length;
}

}  // namespace tacs
