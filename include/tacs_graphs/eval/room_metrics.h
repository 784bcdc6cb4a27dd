// Room segmentation metrics (docs/DESIGN.md "Evaluation", paper Sec. IV-B-2).
//
// Regions are compared as rasterised 2D areas on a grid of `cell`: a ground-truth room is the set
// of cells whose centre lies in its polygon; an estimated room is its floor
// (scene_graph/room_floor.h: its free space extended up to `floor_reach` towards its own walls,
// never across a wall), or, for a segmenter scored on its own (bench_rooms), the cells within
// `point_radius` of its free-space points, where the clearance the free space keeps from walls
// and furniture lowers the Dice of even a perfect segmentation.
//  - Against ground truth: estimated and ground-truth rooms are matched one-to-one, greedily by
//    decreasing Dice = 2|A n B| / (|A| + |B|), pairs below `min_dice` never match. Precision =
//    matched / estimated rooms, recall = matched / ground-truth rooms, F1 their harmonic mean;
//    each ground-truth room reports the Dice of its match (0 when unmatched).
//  - Between two runs (paper eq. 5, DCS): rooms of the two runs are matched one-to-one greedily
//    by Dice among overlapping ("spatially close") pairs; DCS = sum of the matched Dice over
//    max(N_a, N_b), so a room found in one run only counts as 0.
//  - Over K trials: N_room (mean room count), sigma_room (population standard deviation of the
//    counts) and the DCS averaged over all pairs of trials.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <unordered_set>
#include <vector>

#include "tacs_graphs/scene_graph/scene_graph.h"
#include "tacs_graphs/sim/world.h"

namespace tacs {

struct RoomMetricsConfig {
  double cell = 0.1;           // raster cell [m]
  double point_radius = 0.25;  // footprint of a free-space point [m]
  double min_dice = 0.5;       // least Dice of a match against ground truth [-]
  double floor_reach = 1.6;    // RoomFloorConfig::reach_m of the estimated rooms' floors [m]

  template <class V>
  void visit(V& v) {
    v("cell", cell);
    v("point_radius", point_radius);
    v("min_dice", min_dice);
    v("floor_reach", floor_reach);
  }
  /// Throws ConfigError naming the field ("room_metrics.<field>").
  void validate() const;
};

/// A rasterised region: keys of the grid cells it covers.
using CellSet = std::unordered_set<int64_t>;

CellSet rasterizePolygon(const sim::Polygon2& polygon, double cell);
CellSet rasterizePoints(const std::vector<Eigen::Vector2d>& points, double cell, double radius);
/// 2|A n B| / (|A| + |B|); 0 when both are empty.
double dice(const CellSet& a, const CellSet& b);
/// Area of a region [m^2].
inline double cellArea(const CellSet& s, double cell) { return s.size() * cell * cell; }

/// An estimated room as the cells it covers.
struct RoomRegion {
  uint32_t id = 0;
  CellSet cells;
};
/// Each room of the graph as its floor (scene_graph/room_floor.h), in the graph's frame.
std::vector<RoomRegion> floorRegions(const SceneGraph& graph, const RoomMetricsConfig& config = {});
/// Each room as the cells within `point_radius` of its free-space points.
std::vector<RoomRegion> freeSpaceRegions(const std::vector<RoomNode>& rooms,
                                         const RoomMetricsConfig& config = {});

struct GroundTruthRoomScore {
  std::string id;
  std::string kind;
  int matched_room = -1;   // id of the matched estimated room, -1 when none
  double dice = 0.0;       // Dice with the matched room (0 when unmatched)
  double best_dice = 0.0;  // best Dice of any estimated room, matched or not
};

struct RoomMetrics {
  size_t estimated = 0;
  size_t ground_truth = 0;
  size_t matched = 0;
  double precision = 0.0;
  double recall = 0.0;
  double f1 = 0.0;
  double mean_dice = 0.0;  // over ground-truth rooms, unmatched ones count 0
  std::vector<GroundTruthRoomScore> rooms;
};

RoomMetrics evaluateRooms(const std::vector<RoomRegion>& estimated,
                          const std::vector<sim::Room>& ground_truth,
                          const RoomMetricsConfig& config = {});

struct RunConsistency {
  double dcs = 0.0;            // eq. 5 summed over matched pairs / max(N_a, N_b)
  size_t matched = 0;          // pairs matched (overlapping)
  double matched_share = 0.0;  // pairs with Dice >= 0.5 / max(N_a, N_b)
};

/// DCS between the rooms of two runs (1 when both runs have no room).
RunConsistency compareRuns(const std::vector<RoomRegion>& a, const std::vector<RoomRegion>& b,
                           const RoomMetricsConfig& config = {});

struct TrialSummary {
  double n_room = 0.0;      // mean number of rooms
  double sigma_room = 0.0;  // population standard deviation of the counts
  double dcs = 0.0;         // mean DCS over all pairs of trials (1 with fewer than two trials)
};

TrialSummary summarizeTrials(const std::vector<std::vector<RoomRegion>>& trials,
                             const RoomMetricsConfig& config = {});

}  // namespace tacs
