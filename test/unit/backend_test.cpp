// The backend end to end on a synthetic room: keyframes with drifting odometry, walls seen from
// every keyframe, a loop closure; landmarks must stay unique and the trajectory must be corrected.
#include "tacs_graphs/backend/backend.h"

#include <gtest/gtest.h>

#include "tacs_graphs/walls/wall_segment.h"

namespace tacs {
namespace {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

// The four inner faces of an 8 x 6 m room, in the map frame, normals facing in.
std::vector<WallSegment> roomWalls() {
  const auto make = [](Eigen::Vector3d n, double d, Eigen::Vector2d a, Eigen::Vector2d b) {
    WallSegment w;
    w.normal = n;
    w.d = d;
    w.endpoints[0] = a;
    w.endpoints[1] = b;
    w.z_min = 0.0;
    w.z_max = 2.5;
    w.inliers = 500;
    return w;
  };
  return {make({1, 0, 0}, 0.0, {0, 6}, {0, 0}), make({-1, 0, 0}, 8.0, {8, 0}, {8, 6}),
          make({0, 1, 0}, 0.0, {0, 0}, {8, 0}), make({0, -1, 0}, 6.0, {8, 6}, {0, 6})};
}

std::vector<WallSegment> seenFrom(const Pose3& T_map_base) {
  std::vector<WallSegment> out;
  for (const auto& w : roomWalls()) out.push_back(transformWall(w, T_map_base.inverse()));
  return out;
}

TEST(Backend, KeepsOneLandmarkPerWallAndCorrectsDrift) {
  Backend backend{BackendConfig(), WallAssociationConfig()};
  // A loop around the room centre; odometry over-rotates by 0.02 rad per keyframe.
  std::vector<Pose3> truth;
  for (int i = 0; i < 24; ++i) {
    const double a = 2 * M_PI * i / 24;
    truth.push_back(poseFromXyzRpy(4 + 2 * std::cos(a), 3 + 1.5 * std::sin(a), 0, 0, 0, a));
  }
  const Pose3 bias = poseFromXyzRpy(0, 0, 0, 0, 0, 0.02);
  Pose3 odom = truth[0];
  double worst_odometry_error = 0;
  for (size_t i = 0; i < truth.size(); ++i) {
    if (i > 0) odom = odom * truth[i - 1].inverse() * truth[i] * bias;
    worst_odometry_error =
        std::max(worst_odometry_error, (odom.translation() - truth[i].translation()).norm());
    backend.addKeyframe(i, 0.1 * i, odom, Matrix6d::Identity() * 100);
    const auto ids = backend.addWallObservations(i, seenFrom(truth[i]));
    EXPECT_EQ(ids.size(), 4u);
    backend.optimizeIfDue();
  }
  backend.addLoopClosure(0, 23, truth[0].inverse() * truth[23], Matrix6d::Identity() * 1000, 0.01);
  ASSERT_TRUE(backend.optimizeIfDue().has_value());

  EXPECT_EQ(backend.wallMap().landmarks().size(), 4u);
  double worst = 0;
  for (size_t i = 0; i < truth.size(); ++i) {
    worst =
        std::max(worst, (backend.keyframePose(i).translation() - truth[i].translation()).norm());
  }
  EXPECT_GT(worst_odometry_error, 0.5);
  EXPECT_LT(worst, 0.05);
  // map->odom maps the last odometry pose onto the optimised one.
  EXPECT_TRUE((backend.mapToOdom() * odom).isApprox(backend.keyframePose(23), 1e-9));

  const SceneGraph g = backend.sceneGraph();
  EXPECT_EQ(g.keyframes.size(), 24u);
  EXPECT_EQ(g.walls.size(), 4u);
  ASSERT_EQ(g.loops.size(), 1u);
  EXPECT_EQ(g.loops[0].to, 23u);
  EXPECT_GE(backend.optimizations(), 24);
  EXPECT_GT(backend.totalOptimizationMs(), 0.0);
}

TEST(Backend, IgnoresUnknownKeyframesAndDuplicates) {
  Backend backend{BackendConfig(), WallAssociationConfig()};
  backend.addKeyframe(0, 0.0, Pose3::Identity(), Matrix6d::Identity());
  backend.addKeyframe(0, 0.0, Pose3::Identity(), Matrix6d::Identity());  // re-sent
  EXPECT_TRUE(backend.addWallObservations(5, seenFrom(Pose3::Identity())).empty());
  backend.addLoopClosure(0, 9, Pose3::Identity(), Matrix6d::Identity(), 0.0);
  EXPECT_TRUE(backend.sceneGraph().loops.empty());
  EXPECT_EQ(backend.sceneGraph().keyframes.size(), 1u);
}

}  // namespace
}  // namespace tacs
