// CoSG-LCD (paper Sec. III-D): room-triggered loop detection in the synthetic box room.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <map>

#include "common/loop_closure_scene.h"
#include "tacs_graphs/loop_closure/loop_detector.h"

namespace tacs {
namespace {

using test::roomPose;

bool contains(const std::vector<uint32_t>& ids, uint32_t id) {
  return std::find(ids.begin(), ids.end(), id) != ids.end();
}

// First visit of the room: keyframes 0..4 along a curve, estimates exact.
std::vector<uint32_t> addFirstVisit(LoopDetector* detector, const test::BoxRoom& room) {
  const Pose3 poses[] = {roomPose(2.0, 2.0, 0), roomPose(3.0, 2.2, 10), roomPose(4.0, 2.6, 20),
                         roomPose(5.0, 3.0, 30), roomPose(6.0, 3.5, 40)};
  std::vector<uint32_t> ids;
  for (uint32_t id = 0; id < 5; ++id) {
    test::addRoomKeyframe(detector, room, id, poses[id], poses[id]);
    ids.push_back(id);
  }
  return ids;
}

struct Revisit {
  LoopDetection detection;
  Pose3 truth_query;
};

// The robot comes back (keyframe 50) at a known pose; its estimate is off by `error`.
Revisit revisit(LoopDetector* detector, const test::BoxRoom& room, const Pose3& error) {
  Revisit out;
  out.truth_query = roomPose(4.3, 2.9, 35);
  std::vector<uint32_t> room_ids = addFirstVisit(detector, room);
  test::addRoomKeyframe(detector, room, 50, out.truth_query, out.truth_query * error);
  room_ids.push_back(50);
  out.detection = detector->detectInRoom(50, room_ids);
  return out;
}

void expectCorrect(const LoopClosure& loop, const Pose3& truth_query) {
  const Pose3 first[] = {roomPose(2.0, 2.0, 0), roomPose(3.0, 2.2, 10), roomPose(4.0, 2.6, 20),
                         roomPose(5.0, 3.0, 30), roomPose(6.0, 3.5, 40)};
  ASSERT_LT(loop.from, 5u);
  EXPECT_EQ(loop.to, 50u);
  const Pose3 truth = first[loop.from].inverse() * truth_query;
  EXPECT_LT(test::translationError(loop.T_from_to, truth), 0.05);
  EXPECT_LT(test::rotationErrorDeg(loop.T_from_to, truth), 0.5);
}

TEST(LoopClosureCosg, ClosesARevisitWithTheCorrectRelativePose) {
  const test::BoxRoom room;
  LoopDetector detector{LoopClosureConfig()};
  const Revisit r =
      revisit(&detector, room, poseFromXyzRpy(0.05, -0.04, 0.0, 0.0, 0.0, 1.0 * M_PI / 180.0));
  ASSERT_EQ(r.detection.loops.size(), 1u);
  const LoopClosure& loop = r.detection.loops.front();
  EXPECT_EQ(loop.path, LoopPath::kCoarse);
  EXPECT_GE(loop.score, detector.config().cosg.s_coarse);
  expectCorrect(loop, r.truth_query);
  // The information is usable by the backend: symmetric and positive on the diagonal.
  EXPECT_TRUE(loop.information.isApprox(loop.information.transpose()));
  EXPECT_GT(loop.information.diagonal().minCoeff(), 0.0);
  EXPECT_EQ(detector.stats().coarse_loops, 1);
  EXPECT_EQ(detector.stats().detections, 1);
  EXPECT_GT(detector.stats().total_ms, 0.0);
}

TEST(LoopClosureCosg, TiltInformationScaleDampsOnlyRollAndPitch) {
  const test::BoxRoom room;
  const Pose3 error = poseFromXyzRpy(0.05, -0.04, 0.0, 0.0, 0.0, 1.0 * M_PI / 180.0);
  LoopClosureConfig full_config, damped_config;
  full_config.registration.tilt_information_scale = 1.0;
  damped_config.registration.tilt_information_scale = 0.01;
  LoopDetector full{full_config};
  LoopDetector damped{damped_config};
  const Revisit a = revisit(&full, room, error);
  const Revisit b = revisit(&damped, room, error);
  ASSERT_EQ(a.detection.loops.size(), 1u);
  ASSERT_EQ(b.detection.loops.size(), 1u);
  const Eigen::Matrix<double, 6, 6>& I = a.detection.loops.front().information;
  const Eigen::Matrix<double, 6, 6>& J = b.detection.loops.front().information;
  // Same registration, so the Hessians agree but for the rows and columns of rx and ry.
  const double tol = 1e-6 * I.cwiseAbs().maxCoeff();
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) {
      const double factor = ((r == 3 || r == 4) ? 0.1 : 1.0) * ((c == 3 || c == 4) ? 0.1 : 1.0);
      EXPECT_NEAR(J(r, c), factor * I(r, c), tol) << "entry " << r << "," << c;
    }
  }
  EXPECT_GT(I(3, 3), 0.0);
  const Eigen::LLT<Eigen::Matrix<double, 6, 6>> llt(J);
  EXPECT_EQ(llt.info(), Eigen::Success);
}

// Every coarse registration of `d` scored at least S_fine but below S_coarse: weak matches only.
void expectOnlyWeakMatches(const LoopDetection& d, const CosgLoopConfig& c) {
  for (double score : d.coarse_scores) {
    EXPECT_LT(score, c.s_coarse) << "coarse score";
    EXPECT_GE(score, c.s_fine) << "coarse score";
  }
}

TEST(LoopClosureCosg, LargeInitialErrorClosesThroughTheFinePathOnly) {
  const test::BoxRoom room;
  // 1 m and 10 deg off: the narrow gate of the coarse path settles on a wrong pose for every
  // candidate (their scores stay between S_fine and S_coarse), the fine path recovers it.
  for (const Pose3& error : {poseFromXyzRpy(0.707, 0.707, 0.0, 0.0, 0.0, 10.0 * M_PI / 180.0),
                             poseFromXyzRpy(-0.707, -0.707, 0.0, 0.0, 0.0, -10.0 * M_PI / 180.0)}) {
    SCOPED_TRACE(error.translation().transpose());
    LoopClosureConfig coarse_only;
    coarse_only.cosg.max_fine_candidates = 0;
    LoopDetector coarse_detector(coarse_only);
    const Revisit coarse = revisit(&coarse_detector, room, error);
    EXPECT_TRUE(coarse.detection.loops.empty());
    // The nearest max_candidates_per_partition (3) of the 5 first-visit keyframes.
    ASSERT_EQ(coarse.detection.coarse_scores.size(), 3u);
    expectOnlyWeakMatches(coarse.detection, coarse_only.cosg);

    LoopDetector detector{LoopClosureConfig()};
    const Revisit r = revisit(&detector, room, error);
    ASSERT_EQ(r.detection.loops.size(), 1u);
    EXPECT_EQ(r.detection.loops.front().path, LoopPath::kFine);
    EXPECT_GE(r.detection.loops.front().score, detector.config().cosg.s_coarse);
    expectCorrect(r.detection.loops.front(), r.truth_query);
    EXPECT_EQ(detector.stats().fine_loops, 1);
    // 3 coarse registrations and the 3 weak matches refined in 3 stages each.
    EXPECT_EQ(r.detection.registrations, 3 + 3 * 3);
  }
}

TEST(LoopClosureCosg, FinePathStopsWhenTheWideGatesReturnToTheCoarsePose) {
  // Exact estimates, but S_coarse out of reach (as in clutter, where right alignments score
  // below it): the best weak match refined from the estimate comes back to its coarse pose, so
  // the weaker ones are not refined too.
  const test::BoxRoom room;
  LoopClosureConfig config;
  config.cosg.s_coarse = 0.9999;
  LoopDetector detector(config);
  const Revisit r = revisit(&detector, room, Pose3::Identity());
  ASSERT_EQ(r.detection.coarse_scores.size(), 3u);
  expectOnlyWeakMatches(r.detection, config.cosg);
  EXPECT_TRUE(r.detection.loops.empty());
  ASSERT_EQ(r.detection.refined.size(), 1u);
  // The best coarse match is the one refined.
  const double best =
      *std::max_element(r.detection.coarse_scores.begin(), r.detection.coarse_scores.end());
  EXPECT_NEAR(r.detection.refined_scores.front(), best, 0.05);
  EXPECT_EQ(r.detection.registrations, 3 + 3);  // 3 coarse, one weak match in 3 stages
}

TEST(LoopClosureCosg, AWrongRoomGivesNoLoop) {
  // The "revisit" is a different room: a 7 x 5 m room with other furniture.
  test::BoxRoom first, other;
  other.room.hi = {7.0, 5.0, 2.8};
  other.obstacles = {{{1.0, 3.0, 0.0}, {2.5, 4.0, 1.2}}};
  LoopDetector detector{LoopClosureConfig()};
  std::vector<uint32_t> room_ids = addFirstVisit(&detector, first);
  test::addRoomKeyframe(&detector, other, 50, roomPose(4.0, 2.5, 20), roomPose(4.0, 2.5, 20));
  const LoopDetection d = detector.detectInRoom(50, room_ids);
  EXPECT_FALSE(d.registered.empty());
  EXPECT_TRUE(d.loops.empty());
}

TEST(LoopClosureCosg, OnlyOlderKeyframesOfTheRoomWithinDLoopAreTried) {
  const test::BoxRoom room;
  LoopClosureConfig config;
  config.cosg.max_candidates_per_partition = 100;
  LoopDetector detector(config);
  const PointCloud cloud = test::keyframeCloud(room, roomPose(5, 3.5, 0), 1);
  auto add = [&](uint32_t id, double stamp, double x, double y) {
    detector.addKeyframe(id, stamp, roomPose(x, y, 0), cloud);
  };
  add(1, 1.0, 5.0, 3.0);     // in the room, near: tried
  add(2, 2.0, 8.0, 3.0);     // in the room, 4 m away: tried
  add(3, 3.0, 5.5, 3.5);     // near but not in the room: never tried
  add(4, 4.0, 11.0, 3.0);    // in the room but 7 m away (> d_loop): never tried
  add(40, 40.0, 5.0, 3.0);   // in the room but recent by id (query 50 - 40 < 20)
  add(5, 95.0, 5.2, 3.0);    // old id but recent by time (100 - 95 < 20 s)
  add(50, 100.0, 4.0, 3.0);  // the query
  const LoopDetection d = detector.detectInRoom(50, {1, 2, 4, 5, 40, 50});
  EXPECT_TRUE(contains(d.registered, 1));
  EXPECT_TRUE(contains(d.registered, 2));
  for (uint32_t never : {3u, 4u, 5u, 40u, 50u}) {
    EXPECT_FALSE(contains(d.candidates, never)) << never;
    EXPECT_FALSE(contains(d.registered, never)) << never;
  }
  EXPECT_EQ(d.registered.size(), 2u);
}

TEST(LoopClosureCosg, SearchesOnlyTheTwoPartitionsNearestTheQuery) {
  const test::BoxRoom room;
  LoopClosureConfig config;
  config.cosg.partition_length_m = 3.0;  // a room 12 m long: partitions [0,3) [3,6) [6,9) [9,12]
  config.cosg.max_candidates_per_partition = 100;
  config.cosg.max_fine_candidates = 0;
  LoopDetector detector(config);
  const PointCloud cloud = test::keyframeCloud(room, roomPose(5, 3.5, 0), 1);
  std::vector<uint32_t> room_ids;
  for (uint32_t i = 0; i <= 12; ++i) {  // first pass: x = 0 .. 12 m
    detector.addKeyframe(i, i, roomPose(i, 3.0, 0), cloud);
    room_ids.push_back(i);
  }
  detector.addKeyframe(100, 100.0, roomPose(5.0, 3.2, 0), cloud);  // centres 1.5 4.5 7.5 10.5
  room_ids.push_back(100);
  const LoopDetection d = detector.detectInRoom(100, room_ids);
  EXPECT_EQ(d.partitions, 4);
  EXPECT_EQ(d.searched_partitions, (std::vector<int>{1, 2}));
  // x = 1 and x = 2 are within d_loop but in partition 0; x = 10 is in a far partition too.
  for (uint32_t id : d.registered) {
    EXPECT_GE(id, 3u);
    EXPECT_LE(id, 8u);
  }
  EXPECT_EQ(d.registered.size(), 6u);  // x = 3 .. 8
}

// A pass along a long room: keyframes 0..8 at x = 1..9 m, then the query (100) at x = 5.2 m.
// With a detour, the robot leaves the pass after x = 4 m (keyframe 3) and drives `detour` keyframes
// (ids 10.., not in the room) back and forth across the room before it goes on at x = 5 m.
struct LongRoomRevisit {
  LoopDetection detection;
  Pose3 truth_query = roomPose(5.2, 3.3, -20);
};

LongRoomRevisit revisitLongRoom(LoopDetector* detector, const test::BoxRoom& room,
                                uint32_t detour = 0) {
  LongRoomRevisit out;
  std::vector<uint32_t> room_ids;
  for (uint32_t id = 0; id <= 8; ++id) {
    if (id == 4) {
      for (uint32_t k = 0; k < detour; ++k) {
        const Pose3 pose = roomPose(k % 2 == 0 ? 8.5 : 1.5, 5.0, 0);
        test::addRoomKeyframe(detector, room, 10 + k, pose, pose);
      }
    }
    test::addRoomKeyframe(detector, room, id, roomPose(1.0 + id, 3.5, 0),
                          roomPose(1.0 + id, 3.5, 0));
    room_ids.push_back(id);
  }
  test::addRoomKeyframe(detector, room, 100, out.truth_query, out.truth_query);
  out.detection = detector->detectInRoom(100, room_ids);
  return out;
}

void expectCorrect(const LoopClosure& loop, const LongRoomRevisit& r) {
  const Pose3 truth = roomPose(1.0 + loop.from, 3.5, 0).inverse() * r.truth_query;
  EXPECT_LT(test::translationError(loop.T_from_to, truth), 0.05) << loop.from;
  EXPECT_LT(test::rotationErrorDeg(loop.T_from_to, truth), 0.5) << loop.from;
}

TEST(LoopClosureCosg, ALargeRoomGivesTheBestLoopOfEachSearchedPartition) {
  // Fig. 5(b): with L_part = 3 m the pass makes partitions centred at 2.5, 5.5 and 8 m; the query
  // at x = 5.2 searches the two nearest. The robot left the pass after x = 4 m for a detour, so
  // the partitions' best candidates (x = 5 and x <= 3) lie on stretches of the path far apart:
  // one loop each.
  const test::BoxRoom room;
  LoopClosureConfig config;
  config.cosg.partition_length_m = 3.0;
  LoopDetector detector(config);
  const LongRoomRevisit r = revisitLongRoom(&detector, room, 4);
  const LoopDetection& d = r.detection;
  EXPECT_EQ(d.partitions, 3);
  EXPECT_EQ(d.searched_partitions, (std::vector<int>{1, 0}));
  ASSERT_EQ(d.loops.size(), 2u);
  EXPECT_GE(d.loops[0].score, d.loops[1].score);  // best first
  std::vector<uint32_t> from = {d.loops[0].from, d.loops[1].from};
  std::sort(from.begin(), from.end());
  EXPECT_LE(from[0], 2u);  // x = 1..3
  EXPECT_GE(from[1], 4u);  // x = 5..6, after the detour
  EXPECT_LE(from[1], 5u);
  for (const LoopClosure& loop : d.loops) expectCorrect(loop, r);
}

TEST(LoopClosureCosg, PartitionsOnOneStretchOfThePathGiveOneLoop) {
  // The same room passed in one go: the second partition's best candidate lies within L_part of
  // the first's along the path, its loop would repeat the first.
  const test::BoxRoom room;
  LoopClosureConfig config;
  config.cosg.partition_length_m = 3.0;
  LoopDetector detector(config);
  const LongRoomRevisit r = revisitLongRoom(&detector, room);
  const LoopDetection& d = r.detection;
  EXPECT_EQ(d.searched_partitions, (std::vector<int>{1, 0}));
  ASSERT_EQ(d.loops.size(), 1u);
  const double best_score = *std::max_element(d.coarse_scores.begin(), d.coarse_scores.end());
  EXPECT_DOUBLE_EQ(d.loops[0].score, best_score);
  expectCorrect(d.loops[0], r);
}

// Two passes along the room 0.4 m apart: keyframes 0..12 every 0.5 m (x = 2 .. 8 m), then, after
// 40 s, 100.. back the other way; the query is the last keyframe of the second pass. The
// estimates are exact, so a loop's error is what the registration makes of the scans.
struct TwoPasses {
  LoopDetection detection;
  Pose3 truth_from, truth_query;
};

TwoPasses revisitAlongTwoPasses(LoopDetector* detector, const test::BoxRoom& room, double query_x) {
  constexpr double kNoise = 0.03;  // [m] range noise of a VLP-16
  TwoPasses out;
  std::vector<uint32_t> room_ids;
  std::map<uint32_t, Pose3> truth;
  for (uint32_t i = 0; i <= 12; ++i) {
    truth[i] = roomPose(2.0 + 0.5 * i, 3.0, 5);
    detector->addKeyframe(i, i, truth[i], test::keyframeCloud(room, truth[i], i, kNoise));
    room_ids.push_back(i);
  }
  uint32_t id = 100;
  for (double x = 8.0; x >= query_x - 1e-9; x -= 0.5, ++id) {
    truth[id] = roomPose(x, 3.4, 180);
    detector->addKeyframe(id, 40.0 + id, truth[id],
                          test::keyframeCloud(room, truth[id], id, kNoise));
    room_ids.push_back(id);
  }
  out.detection = detector->detectInRoom(id - 1, room_ids);
  if (!out.detection.loops.empty()) {
    out.truth_from = truth.at(out.detection.loops.front().from);
    out.truth_query = truth.at(out.detection.loops.front().to);
  }
  return out;
}

// Several viewpoints fill the gaps between one scan's rings: the submaps measure the loop's
// rotation (tilt) better than the single pair and its translation as well, within a few mm.
TEST(LoopClosureCosg, SubmapsMeasureTheLoopRotationBetterThanTheSinglePair) {
  const test::BoxRoom room;
  LoopClosureConfig single_config, submap_config;
  single_config.registration.submap_length_m = 0.0;
  submap_config.registration.submap_length_m = 4.0;
  double single_deg = 0.0, submap_deg = 0.0;
  for (double query_x : {3.0, 4.5, 6.0}) {
    LoopDetector single(single_config), submap(submap_config);
    const TwoPasses a = revisitAlongTwoPasses(&single, room, query_x);
    const TwoPasses b = revisitAlongTwoPasses(&submap, room, query_x);
    ASSERT_EQ(a.detection.loops.size(), 1u);
    ASSERT_EQ(b.detection.loops.size(), 1u);
    // Same search; the submap registration is one more.
    EXPECT_EQ(a.detection.loops.front().from, b.detection.loops.front().from);
    EXPECT_EQ(b.detection.registrations, a.detection.registrations + 1);
    const Pose3 truth = a.truth_from.inverse() * a.truth_query;
    const LoopClosure& single_loop = a.detection.loops.front();
    const LoopClosure& submap_loop = b.detection.loops.front();
    EXPECT_LT(test::translationError(single_loop.T_from_to, truth), 0.005) << query_x;
    EXPECT_LT(test::translationError(submap_loop.T_from_to, truth), 0.005) << query_x;
    single_deg += test::rotationErrorDeg(single_loop.T_from_to, truth);
    submap_deg += test::rotationErrorDeg(submap_loop.T_from_to, truth);
  }
  EXPECT_LT(submap_deg, 0.75 * single_deg);  // 0.036 against 0.060 deg when written
}

TEST(LoopClosureCosg, NoSearchWithinTheMinimumIntervalAfterALoop) {
  const test::BoxRoom room;
  LoopClosureConfig config;
  config.cosg.min_loop_interval_m = 3.0;
  LoopDetector detector(config);
  const Revisit r = revisit(&detector, room, Pose3::Identity());
  ASSERT_EQ(r.detection.loops.size(), 1u);
  std::vector<uint32_t> room_ids = {0, 1, 2, 3, 4, 50};
  // 1.5 m of travel after the loop: the room's re-detection does not search.
  const Pose3 near = roomPose(5.8, 2.9, 35);
  test::addRoomKeyframe(&detector, room, 51, near, near);
  room_ids.push_back(51);
  const LoopDetection skipped = detector.detectInRoom(51, room_ids);
  EXPECT_NE(skipped.skipped.find("min_loop_interval_m"), std::string::npos) << skipped.skipped;
  EXPECT_EQ(skipped.registrations, 0);
  // 3.5 m: it searches (and closes) again.
  const Pose3 far = roomPose(3.8, 2.9, 35);
  test::addRoomKeyframe(&detector, room, 52, far, far);
  room_ids.push_back(52);
  const LoopDetection searched = detector.detectInRoom(52, room_ids);
  EXPECT_TRUE(searched.skipped.empty()) << searched.skipped;
  EXPECT_EQ(searched.loops.size(), 1u);
}

TEST(LoopClosureCosg, CandidatesFollowUpdatedPoseEstimates) {
  const test::BoxRoom room;
  LoopDetector detector{LoopClosureConfig()};
  const PointCloud cloud = test::keyframeCloud(room, roomPose(5, 3.5, 0), 1);
  detector.addKeyframe(1, 1.0, roomPose(20.0, 3.0, 0), cloud);  // estimated 16 m away
  detector.addKeyframe(50, 100.0, roomPose(4.0, 3.0, 0), cloud);
  EXPECT_TRUE(detector.detectInRoom(50, {1, 50}).registered.empty());
  // An optimisation moves keyframe 1 next to the query; unknown ids are ignored.
  detector.updatePoses({{1, roomPose(5.0, 3.0, 0)}, {77, roomPose(0, 0, 0)}});
  EXPECT_FALSE(detector.hasKeyframe(77));
  EXPECT_EQ(detector.detectInRoom(50, {1, 50}).registered, (std::vector<uint32_t>{1}));
}

TEST(LoopClosureCosg, UnknownQueryOrEmptyRoomIsSkipped) {
  LoopDetector detector{LoopClosureConfig()};
  LoopDetection d = detector.detectInRoom(7, {1, 2});
  EXPECT_FALSE(d.skipped.empty());
  const test::BoxRoom room;
  detector.addKeyframe(7, 0.0, roomPose(5, 3, 0), test::keyframeCloud(room, roomPose(5, 3, 0), 1));
  d = detector.detectInRoom(7, {7, 99});
  EXPECT_FALSE(d.skipped.empty());
  EXPECT_EQ(d.registrations, 0);
}

TEST(LoopClosureCosg, QueryIsTheRoomsNewestKeyframe) {
  // The keyframe that ended an observation may stand past the doorway; the query is the robot's
  // last keyframe inside the re-detected room.
  EXPECT_EQ(cosgQueryKeyframe({3, 41, 17, 40}, 42), 41u);
  EXPECT_EQ(cosgQueryKeyframe({}, 42), 42u);
}

}  // namespace
}  // namespace tacs
