#include "tacs_graphs/rooms/room_extraction.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tacs_graphs/walls/wall_segment.h"

namespace tacs {

namespace {

constexpr int kXPlus = static_cast<int>(WallDirection::kXPlus);
constexpr int kXMinus = static_cast<int>(WallDirection::kXMinus);
constexpr int kYPlus = static_cast<int>(WallDirection::kYPlus);
constexpr int kYMinus = static_cast<int>(WallDirection::kYMinus);

struct Candidate {
  uint32_t id;
  int adjacent;     // score: adjacent length in bins, then adjacent points
  int points;       // adjacent points
  double position;  // coordinate of the wall along the building axis it is orthogonal to [m]
};

constexpr double kBin = 0.2;  // along-wall bins of the adjacency coverage [m]

struct Adjacency {
  int points = 0;        // adjacent free-space points
  int covered_bins = 0;  // bins along the wall holding adjacent points
  int behind_bins = 0;   // bins holding free space just behind the wall
  double covered() const { return covered_bins * kBin; }
};

// Free-space points in front of the wall (its normal faces the room), within the adjacency
// distance and along its extent: the "adjacent points" of paper Sec. III-B-3. Coverage along
// the wall, rather than the raw count, ranks walls, so a short furniture face in the middle of
// the free space does not outrank the room's wall behind the furniture; free space right behind
// a face (within the adjacency distance) marks a face inside the region, not one bounding it.
Adjacency adjacency(const WallLandmark& w, const std::vector<Eigen::Vector3d>& pts,
                    const RoomExtractionConfig& c) {
  const Eigen::Vector2d axis = wallAxis(w.normal);
  const double len = w.length();
  const size_t n_bins = static_cast<size_t>((len + 2.0 * c.extent_margin) / kBin) + 1;
  std::vector<char> front(n_bins, 0), behind(n_bins, 0);
  Adjacency a;
  for (const auto& p : pts) {
    const double s = w.normal.dot(p) + w.d;
    if (std::abs(s) > c.adjacency_distance) continue;
    const double t = (p.head<2>() - w.endpoints[0]).dot(axis) + c.extent_margin;
    if (t < 0.0 || t > len + 2.0 * c.extent_margin) continue;
    if (s > 0.0) {
      ++a.points;
      front[static_cast<size_t>(t / kBin)] = 1;
    } else {
      behind[static_cast<size_t>(t / kBin)] = 1;
    }
  }
  for (size_t i = 0; i < n_bins; ++i) {
    a.covered_bins += front[i];
    a.behind_bins += behind[i];
  }
  return a;
}

// Share of the points whose coordinate along `axis` lies in [lo, hi].
double shareBetween(const std::vector<Eigen::Vector3d>& pts, const Eigen::Vector2d& axis, double lo,
                    double hi) {
  if (pts.empty()) return 0.0;
  size_t n = 0;
  for (const auto& p : pts) {
    const double u = p.head<2>().dot(axis);
    if (u >= lo && u <= hi) ++n;
  }
  return static_cast<double>(n) / pts.size();
}

struct Pair {
  int low = -1, high = -1;  // indices into the candidate lists
  int score = 0;
};

// Best facing pair: the wall facing +axis (low side) below the wall facing -axis (high side),
// far enough apart, with most of the region between them; highest total adjacency wins, which
// is the per-category maximum of the paper whenever that pair is valid.
Pair bestPair(const std::vector<Candidate>& low, const std::vector<Candidate>& high,
              const std::vector<Eigen::Vector3d>& pts, const Eigen::Vector2d& axis,
              const RoomExtractionConfig& c) {
  Pair best;
  for (size_t i = 0; i < low.size(); ++i) {
    for (size_t j = 0; j < high.size(); ++j) {
      const int score = low[i].adjacent + high[j].adjacent;
      if (score <= best.score) continue;
      if (high[j].position - low[i].position < c.min_width) continue;
      if (shareBetween(pts, axis, low[i].position, high[j].position) < c.min_inside_share) continue;
      best = {static_cast<int>(i), static_cast<int>(j), score};
    }
  }
  return best;
}

// Extent [lo, hi] along wall w's axis (from its first endpoint) of its wall line: w and the
// pieces of the same face it continues into across doorways, since a door splits a wall into
// pieces and the room keeps only one of them.
std::pair<double, double> wallLineExtent(uint32_t id, const WallLandmark& w,
                                         const std::map<uint32_t, WallLandmark>& landmarks,
                                         const std::vector<Doorway>& doorways) {
  const Eigen::Vector2d axis = wallAxis(w.normal);
  double lo = 0.0, hi = w.length();
  std::vector<uint32_t> line = {id};
  for (size_t k = 0; k < line.size(); ++k) {
    for (const Doorway& d : doorways) {
      const uint32_t other = d.wall_a == line[k] ? d.wall_b : d.wall_b == line[k] ? d.wall_a : id;
      if (std::find(line.begin(), line.end(), other) != line.end()) continue;
      const auto it = landmarks.find(other);
      if (it == landmarks.end()) continue;
      line.push_back(other);
      for (const auto& e : it->second.endpoints) {
        const double t = (e - w.endpoints[0]).dot(axis);
        lo = std::min(lo, t), hi = std::max(hi, t);
      }
    }
  }
  return {lo, hi};
}

// The region's points that are not behind one of the room's own walls: a point more than the
// margin behind a wall line, within its extent, reached the region through a door in it.
// Points beside a wall's end stay, so an L-shaped room keeps its leg past a shorter wall. A
// corridor is the band between its two walls: past a wall's end lies the next corridor (a
// corner), so there the line has no ends.
std::vector<Eigen::Vector3d> insideOwnWalls(const std::vector<Eigen::Vector3d>& free_space,
                                            const RoomObservation& room,
                                            const std::map<uint32_t, WallLandmark>& landmarks,
                                            const std::vector<Doorway>& doorways,
                                            const RoomExtractionConfig& c) {
  struct Line {
    const WallLandmark* wall;
    double lo, hi;
  };
  std::vector<Line> lines;
  for (int id : room.walls) {
    const auto it = id >= 0 ? landmarks.find(static_cast<uint32_t>(id)) : landmarks.end();
    if (it == landmarks.end()) continue;
    if (room.kind == RoomKind::kCorridor) {
      const double inf = std::numeric_limits<double>::infinity();
      lines.push_back({&it->second, -inf, inf});
    } else {
      const auto [lo, hi] = wallLineExtent(it->first, it->second, landmarks, doorways);
      lines.push_back({&it->second, lo, hi});
    }
  }
  std::vector<Eigen::Vector3d> kept;
  kept.reserve(free_space.size());
  for (const auto& p : free_space) {
    const bool behind = std::any_of(lines.begin(), lines.end(), [&](const Line& l) {
      if (l.wall->normal.dot(p) + l.wall->d >= -c.outside_margin) return false;
      const double t = (p.head<2>() - l.wall->endpoints[0]).dot(wallAxis(l.wall->normal));
      return t >= l.lo && t <= l.hi;
    });
    if (!behind) kept.push_back(p);
  }
  return kept;
}

Eigen::Vector2d axisOf(double yaw, bool x) {
  return x ? Eigen::Vector2d(std::cos(yaw), std::sin(yaw))
           : Eigen::Vector2d(-std::sin(yaw), std::cos(yaw));
}

}  // namespace

std::vector<std::pair<uint32_t, uint32_t>> RoomObservation::wallPairs() const {
  std::vector<std::pair<uint32_t, uint32_t>> out;
  if (hasXPair()) out.emplace_back(walls[kXPlus], walls[kXMinus]);
  if (hasYPair()) out.emplace_back(walls[kYPlus], walls[kYMinus]);
  return out;
}

std::vector<uint32_t> RoomObservation::wallIds() const {
  std::vector<uint32_t> out;
  for (int w : walls) {
    if (w >= 0) out.push_back(static_cast<uint32_t>(w));
  }
  return out;
}

Eigen::Vector2d RoomObservation::xAxis() const { return axisOf(axes_yaw, true); }
Eigen::Vector2d RoomObservation::yAxis() const { return axisOf(axes_yaw, false); }

Eigen::Vector2d RoomObservation::freeSpaceCentroid() const {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const auto& p : free_space) sum += p.head<2>();
  return free_space.empty() ? sum : Eigen::Vector2d(sum / free_space.size());
}

RoomExtractionResult extractRoom(const std::vector<Eigen::Vector3d>& free_space,
                                 const std::map<uint32_t, WallLandmark>& landmarks,
                                 const DominantAxes& axes, const RoomExtractionConfig& config,
                                 const std::vector<Doorway>& doorways) {
  RoomExtractionResult result;
  if (static_cast<int>(free_space.size()) < config.min_free_space_points) {
    result.reason = "free space too small";
    return result;
  }
  const Eigen::Vector2d x_axis = axes.xAxis(), y_axis = axes.yAxis();
  std::array<std::vector<Candidate>, 4> candidates;
  for (const auto& [id, wall] : landmarks) {
    const Adjacency a = adjacency(wall, free_space, config);
    if (a.points == 0 || a.covered() < config.min_adjacent_length) continue;
    if (a.behind_bins > config.max_behind_share * a.covered_bins) continue;
    const int adjacent = a.covered_bins * 100000 + std::min(a.points, 99999);
    const int dir = static_cast<int>(classifyWall(wall.normal, axes));
    const Eigen::Vector2d& axis = dir == kXPlus || dir == kXMinus ? x_axis : y_axis;
    candidates[dir].push_back({id, adjacent, a.points, wall.midpoint().dot(axis)});
  }
  const Pair px = bestPair(candidates[kXPlus], candidates[kXMinus], free_space, x_axis, config);
  const Pair py = bestPair(candidates[kYPlus], candidates[kYMinus], free_space, y_axis, config);
  const bool has_x = px.low >= 0, has_y = py.low >= 0;
  if (!has_x && !has_y) {
    result.reason = "no pair of facing walls bounds the free space";
    return result;
  }
  RoomObservation& room = result.room;
  room.kind = has_x && has_y ? RoomKind::kRoom : RoomKind::kCorridor;
  if (has_x != has_y) {
    result.corridor_width =
        has_x ? candidates[kXMinus][px.high].position - candidates[kXPlus][px.low].position
              : candidates[kYMinus][py.high].position - candidates[kYPlus][py.low].position;
  }
  room.axes_yaw = axes.yaw;
  room.free_space = free_space;
  if (has_x) {
    room.walls[kXPlus] = static_cast<int>(candidates[kXPlus][px.low].id);
    room.walls[kXMinus] = static_cast<int>(candidates[kXMinus][px.high].id);
    result.adjacent_points[kXPlus] = candidates[kXPlus][px.low].points;
    result.adjacent_points[kXMinus] = candidates[kXMinus][px.high].points;
  }
  if (has_y) {
    room.walls[kYPlus] = static_cast<int>(candidates[kYPlus][py.low].id);
    room.walls[kYMinus] = static_cast<int>(candidates[kYMinus][py.high].id);
    result.adjacent_points[kYPlus] = candidates[kYPlus][py.low].points;
    result.adjacent_points[kYMinus] = candidates[kYMinus][py.high].points;
  }
  if (config.outside_margin >= 0.0) {
    auto inside = insideOwnWalls(free_space, room, landmarks, doorways, config);
    if (!inside.empty()) room.free_space = std::move(inside);
  }
  // Start from the free-space centre so a corridor's along-wall coordinate is defined.
  const Eigen::Vector2d c = room.freeSpaceCentroid();
  double z = 0.0;
  for (const auto& p : free_space) z += p.z();
  room.center = Eigen::Vector3d(c.x(), c.y(), z / free_space.size());
  recomputeRoomCenter(landmarks, &room);
  result.found = true;
  return result;
}

void recomputeRoomCenter(const std::map<uint32_t, WallLandmark>& landmarks, RoomObservation* room) {
  const Eigen::Vector2d x_axis = room->xAxis(), y_axis = room->yAxis();
  const Eigen::Vector2d centroid = room->freeSpaceCentroid();
  Eigen::Vector2d uv(room->center.head<2>().dot(x_axis), room->center.head<2>().dot(y_axis));
  const auto midway = [&](int low, int high, const Eigen::Vector2d& axis, double* coord) {
    const auto a = landmarks.find(static_cast<uint32_t>(room->walls[low]));
    const auto b = landmarks.find(static_cast<uint32_t>(room->walls[high]));
    if (room->walls[low] < 0 || room->walls[high] < 0) return false;
    if (a == landmarks.end() || b == landmarks.end()) return true;  // keep the old coordinate
    *coord = 0.5 * (a->second.midpoint().dot(axis) + b->second.midpoint().dot(axis));
    return true;
  };
  // A corridor is centred across its walls; along them the free space places it.
  if (!midway(kXPlus, kXMinus, x_axis, &uv.x()) && !room->free_space.empty()) {
    uv.x() = centroid.dot(x_axis);
  }
  if (!midway(kYPlus, kYMinus, y_axis, &uv.y()) && !room->free_space.empty()) {
    uv.y() = centroid.dot(y_axis);
  }
  const Eigen::Vector2d xy = uv.x() * x_axis + uv.y() * y_axis;
  room->center.x() = xy.x();
  room->center.y() = xy.y();
}

}  // namespace tacs
