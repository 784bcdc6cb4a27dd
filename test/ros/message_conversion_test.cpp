#include "tacs_graphs/ros/message_conversion.h"

#include <gtest/gtest.h>

#include <boost/array.hpp>

namespace tacs {
namespace {

TEST(MessageConversion, PoseRoundTrip) {
  const Pose3 pose = poseFromXyzRpy(1.0, -2.0, 0.5, 0.1, -0.2, 2.5);
  const Pose3 back = fromPoseMsg(toPoseMsg(pose));
  EXPECT_TRUE(back.isApprox(pose, 1e-12));
}

TEST(MessageConversion, TransformCarriesFramesAndStamp) {
  const auto t = toTransformMsg(poseFromXyzRpy(1, 2, 3, 0, 0, 0), "odom", "base_link", 4.25);
  EXPECT_EQ(t.header.frame_id, "odom");
  EXPECT_EQ(t.child_frame_id, "base_link");
  EXPECT_DOUBLE_EQ(t.header.stamp.toSec(), 4.25);
  EXPECT_DOUBLE_EQ(t.transform.translation.y, 2.0);
}

TEST(MessageConversion, InformationMatrixIsRowMajor) {
  Eigen::Matrix<double, 6, 6> m = Eigen::Matrix<double, 6, 6>::Zero();
  m(0, 1) = 5.0;
  boost::array<double, 36> a;
  toMatrixArray(m, &a);
  EXPECT_DOUBLE_EQ(a[1], 5.0);
  EXPECT_DOUBLE_EQ(a[6], 0.0);
  EXPECT_TRUE(fromMatrixArray(a).isApprox(m));
}

}  // namespace
}  // namespace tacs
