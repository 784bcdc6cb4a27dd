#include "tacs_graphs/odometry/carried_voxel_map.h"

#include <cmath>
#include <utility>

#include "tacs_graphs/odometry/parallel.h"

namespace tacs {

CarriedVoxelMap::CarriedVoxelMap(double voxel_m, int num_threads)
    : inv_voxel_(1.0 / voxel_m), num_threads_(num_threads) {}

void CarriedVoxelMap::add(uint32_t id, const Pose3& pose, const GicpCloud& cloud) {
  remove(id);
  Member member;
  const Eigen::Matrix3d R = pose.linear();
  member.points.reserve(cloud.size());
  member.covariances.reserve(cloud.size());
  for (size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d p = pose * cloud.points()[i];
    const Eigen::Vector3d scaled = (p * inv_voxel_).array().floor();
    if (!scaled.allFinite() || scaled.cwiseAbs().maxCoeff() > 1e18) continue;
    member.points.push_back(p);
    member.covariances.push_back(R * cloud.covariances()[i] * R.transpose());
  }
  insert(&member);
  members_.emplace(id, std::move(member));
}

void CarriedVoxelMap::insert(Member* member) {
  member->voxel.resize(member->points.size());
  for (size_t i = 0; i < member->points.size(); ++i) {
    const Eigen::Vector3d scaled = (member->points[i] * inv_voxel_).array().floor();
    const size_t v =
        index_.insert({static_cast<int64_t>(scaled.x()), static_cast<int64_t>(scaled.y()),
                       static_cast<int64_t>(scaled.z()), 0});
    if (v == voxels_.size()) voxels_.emplace_back();
    Voxel& voxel = voxels_[v];
    occupied_ += voxel.count == 0;
    voxel.sum += member->points[i];
    voxel.cov_sum += member->covariances[i];
    ++voxel.count;
    voxel.dirty = true;
    member->voxel[i] = static_cast<uint32_t>(v);
  }
}

void CarriedVoxelMap::remove(uint32_t id) {
  const auto it = members_.find(id);
  if (it == members_.end()) return;
  const Member& member = it->second;
  for (size_t i = 0; i < member.voxel.size(); ++i) {
    Voxel& voxel = voxels_[member.voxel[i]];
    voxel.dirty = true;
    if (--voxel.count == 0) {  // exactly empty, not a residue of the subtraction
      voxel.sum.setZero();
      voxel.cov_sum.setZero();
      --occupied_;
    } else {
      voxel.sum -= member.points[i];
      voxel.cov_sum -= member.covariances[i];
    }
  }
  members_.erase(it);
  if (voxels_.size() > 2 * occupied_ + 1024) reindex();
}

void CarriedVoxelMap::reindex() {
  index_ = VoxelIndex(2 * occupied_);
  voxels_.clear();
  occupied_ = 0;
  for (auto& [id, member] : members_) insert(&member);
}

GicpCloud::ConstPtr CarriedVoxelMap::cloud() {
  // A single member keeps its disc; a mean of discs (a wall seen from several keyframes, or an
  // edge where two walls meet) is made a disc again about its best plane.
  parallelFor(static_cast<int64_t>(voxels_.size()), num_threads_, [&](int64_t i) {
    Voxel& v = voxels_[i];
    if (!v.dirty || v.count == 0) return;
    v.point = v.sum / v.count;
    v.covariance = v.count == 1 ? v.cov_sum : planeRegularized(v.cov_sum);
    v.dirty = false;
  });
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Matrix3d> covariances;
  points.reserve(occupied_);
  covariances.reserve(occupied_);
  for (const Voxel& v : voxels_) {
    if (v.count == 0) continue;
    points.push_back(v.point);
    covariances.push_back(v.covariance);
  }
  return GicpCloud::fromParts(std::move(points), std::move(covariances));
}

}  // namespace tacs
