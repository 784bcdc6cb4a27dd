// The local map of carried covariances (odometry.local_map_covariances: carried), kept up to date
// as keyframes join and leave the window instead of merged anew at each keyframe: a joining
// keyframe is hashed once, a leaving one is subtracted from the voxels it was added to, and only
// the voxels they touched are made discs again. The result is mergeGicpClouds() of the window, up
// to the order of floating-point sums and of the points.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <vector>

#include "tacs_graphs/common/types.h"
#include "tacs_graphs/odometry/gicp.h"
#include "tacs_graphs/odometry/voxel_index.h"

namespace tacs {

class CarriedVoxelMap {
 public:
  CarriedVoxelMap(double voxel_m, int num_threads);

  /// Adds a keyframe's points and covariances (`cloud`, in its own frame) placed by `pose`.
  /// An id already present is replaced.
  void add(uint32_t id, const Pose3& pose, const GicpCloud& cloud);
  /// Removes the keyframe's contribution; unknown ids are ignored.
  void remove(uint32_t id);
  /// The occupied voxels: centroid and plane-regularised mean covariance each, with a KD-tree.
  GicpCloud::ConstPtr cloud();

  size_t keyframes() const { return members_.size(); }

 private:
  struct Voxel {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d cov_sum = Eigen::Matrix3d::Zero();
    int count = 0;
    bool dirty = true;  // point and covariance below are out of date
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
  };
  // What a keyframe added: per point its voxel, map-frame point and rotated covariance.
  struct Member {
    std::vector<uint32_t> voxel;
    std::vector<Eigen::Vector3d> points;
    std::vector<Eigen::Matrix3d> covariances;
  };

  void insert(Member* member);
  void reindex();  // drops emptied voxels from the index once they outnumber the occupied ones

  double inv_voxel_;
  int num_threads_;
  VoxelIndex index_{1024};
  std::vector<Voxel> voxels_;
  std::map<uint32_t, Member> members_;
  size_t occupied_ = 0;
};

}  // namespace tacs
