// The distance-threshold loop detection baseline (hdl_graph_slam style).
#include <gtest/gtest.h>

#include <algorithm>

#include "common/loop_closure_scene.h"
#include "tacs_graphs/loop_closure/loop_detector.h"

namespace tacs {
namespace {

using test::roomPose;

// Out along y = 3.5 from x = 1 to 9 and back, a keyframe every metre: ids 0..8 go out
// (travelled 0..8 m), ids 9..16 come back at x = 8..1 (travelled 9..16 m).
Pose3 outAndBack(uint32_t id) {
  const double x = id <= 8 ? 1.0 + id : 17.0 - id;
  return roomPose(x, 3.5, id <= 8 ? 0.0 : 180.0);
}

TEST(LoopClosureDistance, CandidatesAreNearInXyAndFarBackAlongThePath) {
  const test::BoxRoom room;
  LoopClosureConfig config;
  config.method = LoopMethod::kDistance;
  LoopDetector detector(config);
  for (uint32_t id = 0; id <= 12; ++id) {
    test::addRoomKeyframe(&detector, room, id, outAndBack(id), outAndBack(id));
  }
  EXPECT_NEAR(detector.accumulatedDistance(12), 12.0, 1e-9);
  // Keyframe 12 is at x = 5 after 12 m: only ids with travelled < 4 m (x = 1..4) are far enough
  // back, and of those x = 2, 3, 4 lie within 3 m. Ids 5..7 are near but too recent.
  const LoopDetection d = detector.detectByDistance(12);
  std::vector<uint32_t> candidates = d.candidates;
  std::sort(candidates.begin(), candidates.end());
  EXPECT_EQ(candidates, (std::vector<uint32_t>{1, 2, 3}));
  ASSERT_EQ(d.loops.size(), 1u);
  const LoopClosure& loop = d.loops.front();
  EXPECT_EQ(loop.path, LoopPath::kDistance);
  EXPECT_EQ(loop.to, 12u);
  EXPECT_LT(loop.fitness, config.distance.fitness_threshold);
  const Pose3 truth = outAndBack(loop.from).inverse() * outAndBack(12);
  EXPECT_LT(test::translationError(loop.T_from_to, truth), 0.05);
  EXPECT_LT(test::rotationErrorDeg(loop.T_from_to, truth), 0.5);
}

// Out, back and out again along the same line: the clouds of the later passes are released
// (one cloud per place in this test), so only the first pass's keyframes are candidates.
TEST(LoopClosureDistance, ReleasedCloudsAreNoCandidates) {
  const auto outBackOut = [](uint32_t id) {
    return id <= 16 ? outAndBack(id) : roomPose(id - 15.0, 3.5, 0.0);
  };
  const test::BoxRoom room;
  LoopClosureConfig config;
  config.method = LoopMethod::kDistance;
  config.cloud_retention.place_radius_m = 0.6;
  config.cloud_retention.max_keyframes_per_place = 1;
  config.cloud_retention.min_age_keyframes = 2;
  LoopDetector detector(config);
  for (uint32_t id = 0; id <= 24; ++id) {
    test::addRoomKeyframe(&detector, room, id, outBackOut(id), outBackOut(id));
  }
  // Ids 9..22 stand where a first-pass keyframe stands; 23 and 24 are still young.
  EXPECT_EQ(detector.keyframeCount(), 25u);
  EXPECT_EQ(detector.cloudCount(), 11u);
  // Keyframe 24 (x = 9, 24 m travelled): x = 6..9 within 3 m and far enough back are ids 5..8
  // of the first pass and ids 9..11 of the way back, whose clouds are gone.
  const LoopDetection d = detector.detectByDistance(24);
  std::vector<uint32_t> candidates = d.candidates;
  std::sort(candidates.begin(), candidates.end());
  EXPECT_EQ(candidates, (std::vector<uint32_t>{5, 6, 7, 8}));
  ASSERT_EQ(d.loops.size(), 1u);
  EXPECT_LE(d.loops.front().from, 8u);
}

TEST(LoopClosureDistance, WaitsMinEdgeIntervalAfterALoop) {
  const test::BoxRoom room;
  LoopClosureConfig config;
  config.method = LoopMethod::kDistance;
  config.distance.min_edge_interval_m = 3.0;
  LoopDetector detector(config);
  int loops = 0;
  std::vector<uint32_t> skipped;
  for (uint32_t id = 0; id <= 16; ++id) {
    test::addRoomKeyframe(&detector, room, id, outAndBack(id), outAndBack(id));
    const LoopDetection d = detector.detectByDistance(id);
    if (!d.skipped.empty()) {
      EXPECT_EQ(d.registrations, 0);
      skipped.push_back(id);
    }
    loops += static_cast<int>(d.loops.size());
  }
  // The first revisit with a candidate is id 11 (x = 6 after 11 m; travelled < 3 m gives
  // x = 1..3, and x = 3 is 3 m away): it closes; 12 and 13 are within 3 m of travel and are
  // skipped; 14 closes again; 15 and 16 are skipped.
  EXPECT_EQ(skipped, (std::vector<uint32_t>{12, 13, 15, 16}));
  EXPECT_EQ(loops, 2);
  EXPECT_EQ(detector.stats().distance_loops, 2);
}

TEST(LoopClosureDistance, RejectsAPoorFit) {
  // The candidates are in another room: nothing fits within the fitness threshold.
  test::BoxRoom first, other;
  other.room.hi = {7.0, 5.0, 2.8};
  other.obstacles = {{{1.0, 3.0, 0.0}, {2.5, 4.0, 1.2}}};
  LoopClosureConfig config;
  config.distance.fitness_threshold = 0.01;
  LoopDetector detector(config);
  for (uint32_t id = 0; id <= 12; ++id) {
    test::addRoomKeyframe(&detector, id < 12 ? first : other, id, outAndBack(id), outAndBack(id));
  }
  const LoopDetection d = detector.detectByDistance(12);
  EXPECT_EQ(d.registrations, 3);
  EXPECT_TRUE(d.loops.empty());
}

}  // namespace
}  // namespace tacs
