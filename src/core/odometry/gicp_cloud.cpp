#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "tacs_graphs/odometry/carried_voxel_map.h"
#include "tacs_graphs/odometry/gicp.h"
#include "tacs_graphs/odometry/kd_tree.h"
#include "tacs_graphs/odometry/parallel.h"

namespace tacs {

struct GicpCloud::Index {
  explicit Index(const std::vector<Eigen::Vector3d>& points) : tree(points) {}
  KdTree3 tree;
};

GicpCloud::~GicpCloud() = default;

void GicpCloud::buildIndex() { index_ = std::make_unique<Index>(points_); }

Eigen::Matrix3d planeRegularizedCovariance(const std::vector<Eigen::Vector3d>& points,
                                           const std::vector<uint32_t>& neighbours) {
  if (neighbours.size() < 3) return Eigen::Matrix3d::Identity();
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (uint32_t j : neighbours) mean += points[j];
  mean /= static_cast<double>(neighbours.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (uint32_t j : neighbours) {
    const Eigen::Vector3d d = points[j] - mean;
    cov.noalias() += d * d.transpose();
  }
  return planeRegularized(cov);
}

Eigen::Matrix3d planeRegularized(const Eigen::Matrix3d& cov) {
  // V diag(f, 1, 1) V^T = I - (1 - f) n n^T (f = kGicpPlaneVariance) with n the plane normal (the
  // eigenvector of the smallest eigenvalue), so only that one vector is needed: it is orthogonal
  // to the rows of cov - lambda_min I, hence their largest cross product.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(cov, Eigen::EigenvaluesOnly);
  const Eigen::Matrix3d shifted = cov - eig.eigenvalues()[0] * Eigen::Matrix3d::Identity();
  const Eigen::Vector3d c01 = shifted.row(0).cross(shifted.row(1));
  const Eigen::Vector3d c02 = shifted.row(0).cross(shifted.row(2));
  const Eigen::Vector3d c12 = shifted.row(1).cross(shifted.row(2));
  const double n01 = c01.squaredNorm(), n02 = c02.squaredNorm(), n12 = c12.squaredNorm();
  const double best = std::max({n01, n02, n12});
  Eigen::Vector3d normal;
  if (best > 1e-12 * std::pow(cov.trace(), 4)) {
    normal = (best == n01 ? c01 : best == n02 ? c02 : c12) / std::sqrt(best);
  } else {  // the two smallest eigenvalues (nearly) coincide: a line or a blob, no unique normal
    eig.computeDirect(cov);
    normal = eig.eigenvectors().col(0);
  }
  return Eigen::Matrix3d::Identity() - (1.0 - kGicpPlaneVariance) * normal * normal.transpose();
}

GicpCloud::ConstPtr GicpCloud::build(const PointCloud& cloud, int k_neighbors, int num_threads) {
  std::vector<Eigen::Vector3d> points;
  points.reserve(cloud.points.size());
  for (const auto& p : cloud.points) {
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) {
      points.emplace_back(p.x, p.y, p.z);
    }
  }
  return build(std::move(points), k_neighbors, num_threads);
}

GicpCloud::ConstPtr GicpCloud::build(std::vector<Eigen::Vector3d> points, int k_neighbors,
                                     int num_threads) {
  std::shared_ptr<GicpCloud> cloud(new GicpCloud);
  cloud->points_ = std::move(points);
  cloud->buildIndex();
  const auto& pts = cloud->points_;
  cloud->covariances_.resize(pts.size());
  parallelFor(static_cast<int64_t>(pts.size()), num_threads, [&](int64_t i) {
    thread_local std::vector<uint32_t> indices;
    thread_local std::vector<double> dist_sq;
    cloud->knn(pts[i], k_neighbors, &indices, &dist_sq);
    cloud->covariances_[i] = planeRegularizedCovariance(pts, indices);
  });
  return cloud;
}

GicpCloud::ConstPtr mergeGicpClouds(
    const std::vector<std::pair<Pose3, GicpCloud::ConstPtr>>& clouds, double voxel_m,
    int num_threads) {
  CarriedVoxelMap map(voxel_m, num_threads);
  for (size_t i = 0; i < clouds.size(); ++i) {
    map.add(static_cast<uint32_t>(i), clouds[i].first, *clouds[i].second);
  }
  return map.cloud();
}

GicpCloud::ConstPtr GicpCloud::fromParts(std::vector<Eigen::Vector3d> points,
                                         std::vector<Eigen::Matrix3d> covariances) {
  std::shared_ptr<GicpCloud> cloud(new GicpCloud);
  if (covariances.size() != points.size())
    covariances.assign(points.size(), Eigen::Matrix3d::Identity());
  cloud->points_ = std::move(points);
  cloud->covariances_ = std::move(covariances);
  cloud->buildIndex();
  return cloud;
}

int64_t GicpCloud::nearest(const Eigen::Vector3d& query, double max_dist_sq, double* dist_sq,
                           int64_t hint) const {
  if (points_.empty()) return -1;
  float found_sq = 0.0f;
  const int64_t found =
      index_->tree.nearest(query.cast<float>(), static_cast<float>(max_dist_sq), &found_sq, hint);
  if (dist_sq) *dist_sq = found_sq;
  return found;
}

void GicpCloud::knn(const Eigen::Vector3d& query, int k, std::vector<uint32_t>* indices,
                    std::vector<double>* dist_sq) const {
  const size_t want = std::min<size_t>(static_cast<size_t>(std::max(k, 0)), points_.size());
  indices->resize(want);
  dist_sq->resize(want);
  if (want == 0) return;
  thread_local std::vector<float> dists;
  dists.resize(want);
  const size_t found = index_->tree.knn(query.cast<float>(), want, indices->data(), dists.data());
  indices->resize(found);
  dist_sq->assign(dists.begin(), dists.begin() + found);
}

}  // namespace tacs
