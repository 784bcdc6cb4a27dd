// Room metrics on hand-made regions: rasterisation, Dice, matching against ground truth, DCS
// between runs and sigma_room over trials.
#include <gtest/gtest.h>

#include "tacs_graphs/eval/room_metrics.h"

namespace tacs {
namespace {

sim::Room gtRoom(const std::string& id, double x0, double x1, double y0, double y1) {
  sim::Room r;
  r.id = id;
  r.polygon = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  return r;
}

// A room whose free space fills [x0,x1] x [y0,y1] with points every 0.1 m (cell centres).
RoomNode estimated(uint32_t id, double x0, double x1, double y0, double y1) {
  RoomNode n;
  n.id = id;
  for (double x = x0 + 0.05; x < x1; x += 0.1) {
    for (double y = y0 + 0.05; y < y1; y += 0.1) n.free_space.emplace_back(x, y);
  }
  return n;
}

RoomMetricsConfig exactCells() {
  RoomMetricsConfig c;
  c.point_radius = 0.0;  // every point covers its own 0.1 m cell only
  return c;
}

// Rooms as the cells of their free-space points.
std::vector<RoomRegion> cells(const std::vector<RoomNode>& rooms) {
  return freeSpaceRegions(rooms, exactCells());
}

TEST(EvalRoomMetrics, RasterisesPolygonsAndPoints) {
  const CellSet square = rasterizePolygon(gtRoom("a", 0, 4, 0, 4).polygon, 0.1);
  EXPECT_EQ(square.size(), 1600u);
  EXPECT_NEAR(cellArea(square, 0.1), 16.0, 1e-9);
  const CellSet half = rasterizePoints(estimated(0, 0, 2, 0, 4).free_space, 0.1, 0.0);
  EXPECT_EQ(half.size(), 800u);
  EXPECT_NEAR(dice(square, half), 2.0 * 800 / 2400, 1e-12);
  EXPECT_NEAR(dice(square, square), 1.0, 1e-12);
  // A footprint radius grows a single point into a disc.
  const CellSet disc = rasterizePoints({{0.05, 0.05}}, 0.1, 0.25);
  EXPECT_GT(disc.size(), 15u);
  EXPECT_LT(disc.size(), 25u);
}

TEST(EvalRoomMetrics, MatchesOneToOneAgainstGroundTruth) {
  const std::vector<sim::Room> gt = {gtRoom("a", 0, 4, 0, 4), gtRoom("b", 4, 8, 0, 4)};
  // Room a found well, room b split in two halves: each half has Dice 0.67, only one matches.
  const std::vector<RoomNode> est = {estimated(0, 0, 4, 0, 3.6), estimated(1, 4, 6, 0, 4),
                                     estimated(2, 6, 8, 0, 4)};
  const RoomMetrics m = evaluateRooms(cells(est), gt, exactCells());
  EXPECT_EQ(m.estimated, 3u);
  EXPECT_EQ(m.ground_truth, 2u);
  EXPECT_EQ(m.matched, 2u);
  EXPECT_NEAR(m.precision, 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(m.recall, 1.0, 1e-12);
  EXPECT_NEAR(m.f1, 0.8, 1e-12);
  EXPECT_EQ(m.rooms[0].matched_room, 0);
  EXPECT_NEAR(m.rooms[0].dice, 2.0 * 1440 / 3040, 1e-12);
  EXPECT_NEAR(m.rooms[1].dice, 2.0 * 800 / 2400, 1e-12);
  EXPECT_NEAR(m.mean_dice, 0.5 * (m.rooms[0].dice + m.rooms[1].dice), 1e-12);

  // Under-segmentation: one region over both rooms matches one of them only.
  const RoomMetrics under = evaluateRooms(cells({estimated(0, 0, 8, 0, 4)}), gt, exactCells());
  EXPECT_EQ(under.matched, 1u);
  EXPECT_NEAR(under.rooms[0].best_dice, 2.0 * 1600 / 4800, 1e-12);
  EXPECT_NEAR(under.rooms[1].best_dice, 2.0 * 1600 / 4800, 1e-12);
  EXPECT_NEAR(under.recall, 0.5, 1e-12);
  EXPECT_NEAR(under.f1, 2.0 / 3.0, 1e-12);
}

TEST(EvalRoomMetrics, DiceScoreBetweenRunsAndTrialStatistics) {
  const std::vector<RoomNode> run1 = {estimated(0, 0, 4, 0, 4), estimated(1, 4, 8, 0, 4)};
  const std::vector<RoomNode> run2 = {estimated(5, 0, 4, 0, 2), estimated(6, 4, 8, 0, 4)};
  const RunConsistency same = compareRuns(cells(run1), cells(run1), exactCells());
  EXPECT_NEAR(same.dcs, 1.0, 1e-12);
  const RunConsistency c = compareRuns(cells(run1), cells(run2), exactCells());
  EXPECT_EQ(c.matched, 2u);
  EXPECT_NEAR(c.dcs, 0.5 * (2.0 * 800 / 2400 + 1.0), 1e-12);
  // A room found in one run only counts as 0.
  const RunConsistency missing = compareRuns(cells(run1), cells({run1[0]}), exactCells());
  EXPECT_NEAR(missing.dcs, 0.5, 1e-12);
  EXPECT_NEAR(missing.matched_share, 0.5, 1e-12);

  // Counts 2, 2, 4: N_room 2.67, sigma_room 0.943 (population standard deviation).
  const std::vector<RoomNode> four = {estimated(0, 0, 2, 0, 4), estimated(1, 2, 4, 0, 4),
                                      estimated(2, 4, 6, 0, 4), estimated(3, 6, 8, 0, 4)};
  const TrialSummary s = summarizeTrials({cells(run1), cells(run1), cells(four)}, exactCells());
  EXPECT_NEAR(s.n_room, 8.0 / 3.0, 1e-12);
  EXPECT_NEAR(s.sigma_room, 0.9428, 1e-4);
  EXPECT_GT(s.dcs, 0.3);
  EXPECT_LT(s.dcs, 1.0);
}

}  // namespace
}  // namespace tacs
