// The incrementally kept local map of carried covariances against a fresh merge of the window.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>

#include "common/box_room.h"
#include "tacs_graphs/odometry/carried_voxel_map.h"
#include "tacs_graphs/odometry/preprocess.h"

namespace tacs {
namespace {

// Points (rounded to 1e-6 m) to their covariance: the two maps list their voxels in different
// orders.
std::map<std::array<long, 3>, Eigen::Matrix3d> byPoint(const GicpCloud& cloud) {
  std::map<std::array<long, 3>, Eigen::Matrix3d> out;
  for (size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d& p = cloud.points()[i];
    out[{std::lround(p.x() * 1e6), std::lround(p.y() * 1e6), std::lround(p.z() * 1e6)}] =
        cloud.covariances()[i];
  }
  return out;
}

void expectSameMap(const GicpCloud& a, const GicpCloud& b) {
  ASSERT_EQ(a.size(), b.size());
  const auto pa = byPoint(a), pb = byPoint(b);
  ASSERT_EQ(pa.size(), a.size());
  for (const auto& [key, cov] : pa) {
    const auto it = pb.find(key);
    ASSERT_NE(it, pb.end()) << key[0] << " " << key[1] << " " << key[2];
    EXPECT_TRUE(cov.isApprox(it->second, 1e-6));
  }
}

TEST(CarriedVoxelMap, KeyframesJoiningAndLeavingGiveTheMergeOfTheWindow) {
  const test::BoxRoom room;
  std::vector<Pose3> poses;
  std::vector<GicpCloud::ConstPtr> clouds;
  for (int k = 0; k < 5; ++k) {
    poses.push_back(poseFromXyzRpy(3.0 + 0.8 * k, 2.5 + 0.3 * k, 0.5, 0.0, 0.0, 0.2 * k));
    clouds.push_back(GicpCloud::build(
        preprocess(test::renderScan(room, poses.back(), 10 + k), PreprocessConfig()), 10, 1));
  }
  CarriedVoxelMap map(0.2, 2);
  // A window of three keyframes sliding over the five, as the odometry keeps it.
  for (uint32_t k = 0; k < 5; ++k) {
    map.add(k, poses[k], *clouds[k]);
    if (k >= 3) map.remove(k - 3);
    std::vector<std::pair<Pose3, GicpCloud::ConstPtr>> window;
    for (uint32_t j = k >= 2 ? k - 2 : 0; j <= k; ++j) window.emplace_back(poses[j], clouds[j]);
    EXPECT_EQ(map.keyframes(), window.size());
    expectSameMap(*map.cloud(), *mergeGicpClouds(window, 0.2, 1));
  }
  // An id added again replaces its points; an unknown id is ignored.
  map.add(4, poses[4], *clouds[4]);
  map.remove(99);
  EXPECT_EQ(map.keyframes(), 3u);
  map.remove(2);
  map.remove(3);
  map.remove(4);
  EXPECT_EQ(map.keyframes(), 0u);
  EXPECT_TRUE(map.cloud()->empty());
  // Driving on: emptied voxels are dropped from the index once they outnumber the occupied ones,
  // and the map stays the window's.
  for (uint32_t k = 0; k < 30; ++k) {
    const Pose3 far = Pose3(Eigen::Translation3d(10.0 * k, 0.0, 0.0)) * poses[k % 5];
    map.add(100 + k, far, *clouds[k % 5]);
    if (k >= 1) map.remove(100 + k - 1);
    if (k == 29) expectSameMap(*map.cloud(), *mergeGicpClouds({{far, clouds[k % 5]}}, 0.2, 1));
  }
}

}  // namespace
}  // namespace tacs
