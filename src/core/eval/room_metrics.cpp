#include "tacs_graphs/eval/room_metrics.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "tacs_graphs/common/config.h"
#include "tacs_graphs/scene_graph/room_floor.h"

namespace tacs {

namespace {

int64_t key(int64_t ix, int64_t iy) { return (ix << 32) ^ (iy & 0xffffffff); }

size_t intersection(const CellSet& a, const CellSet& b) {
  const CellSet& small = a.size() < b.size() ? a : b;
  const CellSet& large = a.size() < b.size() ? b : a;
  size_t n = 0;
  for (int64_t c : small) n += large.count(c);
  return n;
}

// One-to-one greedy matching by decreasing score; pairs with score < min never match.
// Returns (i, j, score) of the matches.
std::vector<std::tuple<size_t, size_t, double>> greedyMatch(
    const std::vector<std::vector<double>>& score, double min) {
  std::vector<std::tuple<double, size_t, size_t>> pairs;
  for (size_t i = 0; i < score.size(); ++i) {
    for (size_t j = 0; j < score[i].size(); ++j) {
      if (score[i][j] >= min && score[i][j] > 0.0) pairs.emplace_back(score[i][j], i, j);
    }
  }
  std::sort(pairs.begin(), pairs.end(),
            [](const auto& a, const auto& b) { return std::get<0>(a) > std::get<0>(b); });
  std::vector<char> used_i(score.size(), 0), used_j(score.empty() ? 0 : score[0].size(), 0);
  std::vector<std::tuple<size_t, size_t, double>> out;
  for (const auto& [s, i, j] : pairs) {
    if (used_i[i] || used_j[j]) continue;
    used_i[i] = used_j[j] = 1;
    out.emplace_back(i, j, s);
  }
  return out;
}

}  // namespace

void RoomMetricsConfig::validate() const {
  requireConfig(cell > 0.0, "room_metrics.cell", "must be > 0");
  requireConfig(point_radius >= 0.0, "room_metrics.point_radius", "must be >= 0");
  requireConfig(min_dice > 0.0 && min_dice <= 1.0, "room_metrics.min_dice", "must be in (0, 1]");
  requireConfig(floor_reach >= 0.0, "room_metrics.floor_reach", "must be >= 0");
}

std::vector<RoomRegion> floorRegions(const SceneGraph& graph, const RoomMetricsConfig& config) {
  config.validate();
  std::vector<RoomRegion> out;
  for (const auto& [id, cells] :
       roomFloors(graph, {config.cell, config.point_radius, config.floor_reach})) {
    RoomRegion r;
    r.id = id;
    for (const auto& c : cells) r.cells.insert(key(c.x(), c.y()));
    out.push_back(std::move(r));
  }
  return out;
}

std::vector<RoomRegion> freeSpaceRegions(const std::vector<RoomNode>& rooms,
                                         const RoomMetricsConfig& config) {
  config.validate();
  std::vector<RoomRegion> out;
  for (const auto& room : rooms) {
    out.push_back({room.id, rasterizePoints(room.free_space, config.cell, config.point_radius)});
  }
  return out;
}

CellSet rasterizePolygon(const sim::Polygon2& polygon, double cell) {
  CellSet out;
  if (polygon.size() < 3) return out;
  Eigen::Vector2d lo = polygon[0], hi = polygon[0];
  for (const auto& p : polygon) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  for (int64_t ix = static_cast<int64_t>(std::floor(lo.x() / cell));
       ix <= static_cast<int64_t>(std::floor(hi.x() / cell)); ++ix) {
    for (int64_t iy = static_cast<int64_t>(std::floor(lo.y() / cell));
         iy <= static_cast<int64_t>(std::floor(hi.y() / cell)); ++iy) {
      const Eigen::Vector2d c((ix + 0.5) * cell, (iy + 0.5) * cell);
      if (sim::pointInPolygon(polygon, c)) out.insert(key(ix, iy));
    }
  }
  return out;
}

CellSet rasterizePoints(const std::vector<Eigen::Vector2d>& points, double cell, double radius) {
  CellSet out;
  const int64_t reach = static_cast<int64_t>(std::ceil(radius / cell));
  for (const auto& p : points) {
    const int64_t cx = static_cast<int64_t>(std::floor(p.x() / cell));
    const int64_t cy = static_cast<int64_t>(std::floor(p.y() / cell));
    for (int64_t ix = cx - reach; ix <= cx + reach; ++ix) {
      for (int64_t iy = cy - reach; iy <= cy + reach; ++iy) {
        const Eigen::Vector2d c((ix + 0.5) * cell, (iy + 0.5) * cell);
        // The point's own cell always counts (radius 0 still covers one cell).
        if ((ix == cx && iy == cy) || (c - p).norm() <= radius) out.insert(key(ix, iy));
      }
    }
  }
  return out;
}

double dice(const CellSet& a, const CellSet& b) {
  if (a.empty() && b.empty()) return 0.0;
  return 2.0 * intersection(a, b) / static_cast<double>(a.size() + b.size());
}

RoomMetrics evaluateRooms(const std::vector<RoomRegion>& estimated,
                          const std::vector<sim::Room>& ground_truth,
                          const RoomMetricsConfig& config) {
  config.validate();
  RoomMetrics m;
  m.estimated = estimated.size();
  m.ground_truth = ground_truth.size();
  std::vector<CellSet> gt;
  for (const auto& r : ground_truth) gt.push_back(rasterizePolygon(r.polygon, config.cell));
  std::vector<std::vector<double>> score(gt.size(), std::vector<double>(estimated.size(), 0.0));
  for (size_t g = 0; g < gt.size(); ++g) {
    GroundTruthRoomScore s;
    s.id = ground_truth[g].id;
    s.kind = ground_truth[g].kind;
    for (size_t e = 0; e < estimated.size(); ++e) {
      score[g][e] = dice(gt[g], estimated[e].cells);
      s.best_dice = std::max(s.best_dice, score[g][e]);
    }
    m.rooms.push_back(s);
  }
  for (const auto& [g, e, d] : greedyMatch(score, config.min_dice)) {
    m.rooms[g].matched_room = static_cast<int>(estimated[e].id);
    m.rooms[g].dice = d;
    ++m.matched;
  }
  m.precision = m.estimated ? static_cast<double>(m.matched) / m.estimated : 0.0;
  m.recall = m.ground_truth ? static_cast<double>(m.matched) / m.ground_truth : 0.0;
  m.f1 =
      m.precision + m.recall > 0.0 ? 2.0 * m.precision * m.recall / (m.precision + m.recall) : 0.0;
  for (const auto& r : m.rooms) m.mean_dice += r.dice;
  if (!m.rooms.empty()) m.mean_dice /= m.rooms.size();
  return m;
}

RunConsistency compareRuns(const std::vector<RoomRegion>& a, const std::vector<RoomRegion>& b,
                           const RoomMetricsConfig& config) {
  config.validate();
  RunConsistency out;
  if (a.empty() && b.empty()) {
    out.dcs = 1.0;
    out.matched_share = 1.0;
    return out;
  }
  std::vector<std::vector<double>> score(a.size(), std::vector<double>(b.size(), 0.0));
  for (size_t i = 0; i < a.size(); ++i) {
    for (size_t j = 0; j < b.size(); ++j) score[i][j] = dice(a[i].cells, b[j].cells);
  }
  const double n = static_cast<double>(std::max(a.size(), b.size()));
  size_t good = 0;
  for (const auto& [i, j, d] : greedyMatch(score, 0.0)) {
    out.dcs += d;
    ++out.matched;
    if (d >= 0.5) ++good;
  }
  out.dcs /= n;
  out.matched_share = good / n;
  return out;
}

TrialSummary summarizeTrials(const std::vector<std::vector<RoomRegion>>& trials,
                             const RoomMetricsConfig& config) {
  TrialSummary s;
  if (trials.empty()) return s;
  for (const auto& t : trials) s.n_room += t.size();
  s.n_room /= trials.size();
  for (const auto& t : trials) s.sigma_room += std::pow(t.size() - s.n_room, 2);
  s.sigma_room = std::sqrt(s.sigma_room / trials.size());
  if (trials.size() < 2) {
    s.dcs = 1.0;
    return s;
  }
  int pairs = 0;
  for (size_t i = 0; i < trials.size(); ++i) {
    for (size_t j = i + 1; j < trials.size(); ++j) {
      s.dcs += compareRuns(trials[i], trials[j], config).dcs;
      ++pairs;
    }
  }
  s.dcs /= pairs;
  return s;
}

}  // namespace tacs
