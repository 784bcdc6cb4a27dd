#include "tacs_graphs/odometry/floor_level.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <vector>

namespace tacs {

namespace {

// A fixed-seed linear congruential generator: the same scan always gives the same floor.
struct Lcg {
  uint64_t state = 0x9e3779b97f4a7c15ull;
  size_t below(size_t n) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<size_t>((state >> 33) % n);
  }
};

// Least-squares plane (centroid, smallest principal axis) of the points within the band.
bool refine(const std::vector<Eigen::Vector3d>& points, double band, FloorPlane* plane) {
  const double d = plane->height_m;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  std::vector<const Eigen::Vector3d*> in;
  for (const auto& p : points) {
    if (std::abs(plane->normal.dot(p) + d) <= band) in.push_back(&p), mean += p;
  }
  if (in.size() < 3) return false;
  mean /= in.size();
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto* p : in) cov += (*p - mean) * (*p - mean).transpose();
  Eigen::Vector3d n = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors().col(0);
  if (n.dot(plane->normal) < 0) n = -n;
  plane->normal = n;
  plane->height_m = -n.dot(mean);
  plane->inliers = in.size();
  return true;
}

}  // namespace

std::optional<FloorPlane> findFloor(const PointCloud& cloud, const FloorSearch& search) {
  const double cos_tilt = std::cos(search.max_tilt_deg * M_PI / 180.0);
  // Candidates: points below the origin within the tilt cone widened by 45 deg (any surface the
  // floor can be seen on).
  std::vector<Eigen::Vector3d> points;
  points.reserve(cloud.size() / 2);
  for (const auto& q : cloud.points) {
    const Eigen::Vector3d p = q.getVector3fMap().cast<double>();
    if (std::isfinite(p.z()) && p.z() < -search.min_height_m * cos_tilt) points.push_back(p);
  }
  if (points.size() < search.min_inliers) return std::nullopt;
  Lcg rng;
  FloorPlane best;
  for (int it = 0; it < search.iterations; ++it) {
    const Eigen::Vector3d& a = points[rng.below(points.size())];
    const Eigen::Vector3d& b = points[rng.below(points.size())];
    const Eigen::Vector3d& c = points[rng.below(points.size())];
    Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() < 1e-6) continue;
    n.normalize();
    if (n.z() < 0) n = -n;
    if (n.z() < cos_tilt) continue;
    const double d = -n.dot(a);  // origin height above the plane (n points up)
    if (d < search.min_height_m) continue;
    size_t count = 0;
    for (const auto& p : points) count += std::abs(n.dot(p) + d) <= search.inlier_distance_m;
    if (count > best.inliers) best = {n, d, count};
  }
  if (best.inliers < search.min_inliers || !refine(points, search.inlier_distance_m, &best)) {
    return std::nullopt;
  }
  if (best.normal.z() < cos_tilt || best.height_m < search.min_height_m) return std::nullopt;
  return best;
}

Eigen::Matrix3d levellingRotation(const Eigen::Vector3d& up) {
  return Eigen::Quaterniond::FromTwoVectors(up.normalized(), Eigen::Vector3d::UnitZ())
      .toRotationMatrix();
}

}  // namespace tacs
