#include <gtest/gtest.h>

#include "tacs_graphs/eval/loop_metrics.h"

namespace tacs {
namespace {

SceneGraph twoKeyframes(const Pose3& measured) {
  SceneGraph g;
  KeyframeNode a, b;
  a.id = 0, a.stamp = 1.0;
  b.id = 1, b.stamp = 2.0;
  g.keyframes[0] = a, g.keyframes[1] = b;
  LoopEdge loop;
  loop.from = 0, loop.to = 1;
  loop.position = measured.translation();
  loop.orientation = Eigen::Quaterniond(measured.rotation());
  g.loops.push_back(loop);
  return g;
}

Trajectory groundTruth() {
  return {{1.0, poseFromXyzRpy(0, 0, 0, 0, 0, 0)}, {2.0, poseFromXyzRpy(2, 1, 0, 0, 0, 0.5)}};
}

TEST(LoopMetrics, AcceptsALoopWithinTolerance) {
  const Pose3 truth = poseFromXyzRpy(2, 1, 0, 0, 0, 0.5);
  const LoopAccuracy acc =
      evaluateLoops(twoKeyframes(truth * poseFromXyzRpy(0.2, 0, 0, 0, 0, 0.03)), groundTruth());
  EXPECT_EQ(acc.loops, 1u);
  EXPECT_EQ(acc.correct, 1u);
  EXPECT_DOUBLE_EQ(acc.precision(), 1.0);
}

TEST(LoopMetrics, RejectsTranslationOrRotationBeyondTolerance) {
  const Pose3 truth = poseFromXyzRpy(2, 1, 0, 0, 0, 0.5);
  EXPECT_EQ(evaluateLoops(twoKeyframes(truth * poseFromXyzRpy(0.4, 0, 0, 0, 0, 0)), groundTruth())
                .correct,
            0u);
  EXPECT_EQ(evaluateLoops(twoKeyframes(truth * poseFromXyzRpy(0, 0, 0, 0, 0, 0.07)), groundTruth())
                .correct,
            0u);
}

TEST(LoopMetrics, CountsKeyframesWithoutGroundTruthApart) {
  Trajectory gt = groundTruth();
  gt[1].stamp = 3.0;  // no ground truth near keyframe 1's stamp
  const LoopAccuracy acc = evaluateLoops(twoKeyframes(Pose3::Identity()), gt);
  EXPECT_EQ(acc.unmatched, 1u);
  EXPECT_EQ(acc.correct, 0u);
  EXPECT_DOUBLE_EQ(acc.precision(), 0.0);
}

}  // namespace
}  // namespace tacs
