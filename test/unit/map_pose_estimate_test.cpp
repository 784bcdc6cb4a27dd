#include "tacs_graphs/pipeline/map_pose_estimate.h"

#include <gtest/gtest.h>

namespace tacs {
namespace {

TEST(MapPoseEstimate, GraphPosesFirstThenTheLatestCorrection) {
  MapPoseEstimate poses;
  for (uint32_t id = 0; id < 3; ++id) {
    poses.addOdometryPose(id, poseFromXyzRpy(1.0 * id, 0, 0, 0, 0, 0));
  }
  EXPECT_FALSE(poses.optimised(0).has_value());
  // Before any graph: odometry poses (identity correction).
  EXPECT_TRUE(poses.mapPose(2)->isApprox(poseFromXyzRpy(2, 0, 0, 0, 0, 0)));
  EXPECT_FALSE(poses.mapPose(7).has_value());
  // The backend moved keyframe 1 by 0.5 m in y (keyframe 0 stays): keyframe 2 follows keyframe 1.
  SceneGraph graph;
  graph.keyframes[0].setPose(poseFromXyzRpy(0, 0, 0, 0, 0, 0));
  graph.keyframes[1].setPose(poseFromXyzRpy(1, 0.5, 0, 0, 0, 0));
  poses.setGraph(graph);
  EXPECT_TRUE(poses.optimised(1)->isApprox(poseFromXyzRpy(1, 0.5, 0, 0, 0, 0)));
  EXPECT_TRUE(poses.mapToOdom().isApprox(poseFromXyzRpy(0, 0.5, 0, 0, 0, 0)));
  EXPECT_TRUE(poses.mapPose(2)->isApprox(poseFromXyzRpy(2, 0.5, 0, 0, 0, 0)));
  EXPECT_TRUE(poses.mapPose(0)->isApprox(Pose3::Identity()));
  EXPECT_EQ(poses.graphPoses().size(), 2u);
}

}  // namespace
}  // namespace tacs
