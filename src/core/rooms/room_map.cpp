#include "tacs_graphs/rooms/room_map.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace tacs {

namespace {

// A region joins a room it touches along at least this many of its cells (0.4 m each by default:
// an aisle's mouth) [-].
constexpr size_t kMinContactCells = 3;
// ... and whose wall pairs enclose at least this share of its points [-].
constexpr double kMinEnclosedShare = 0.8;

// Share of `pts` between the room's facing walls, on every axis it has a pair on.
double shareWithinWalls(const RoomObservation& room, const std::vector<Eigen::Vector3d>& pts,
                        const std::map<uint32_t, WallLandmark>& landmarks) {
  if (pts.empty()) return 0.0;
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> limits;  // (axis, (low, high))
  for (int pair = 0; pair < 2; ++pair) {
    const int lo = room.walls[2 * pair], hi = room.walls[2 * pair + 1];
    const auto a = landmarks.find(static_cast<uint32_t>(lo));
    const auto b = landmarks.find(static_cast<uint32_t>(hi));
    if (lo < 0 || hi < 0 || a == landmarks.end() || b == landmarks.end()) continue;
    const Eigen::Vector2d axis = pair == 0 ? room.xAxis() : room.yAxis();
    const double u0 = a->second.midpoint().dot(axis), u1 = b->second.midpoint().dot(axis);
    limits.emplace_back(axis, Eigen::Vector2d(std::min(u0, u1), std::max(u0, u1)));
  }
  if (limits.empty()) return 0.0;
  size_t inside = 0;
  for (const auto& p : pts) {
    inside += std::all_of(limits.begin(), limits.end(), [&](const auto& l) {
      const double u = p.template head<2>().dot(l.first);
      return u >= l.second.x() && u <= l.second.y();
    });
  }
  return static_cast<double>(inside) / pts.size();
}

// Two views sharing this share of the smaller one's cells touch [-].
constexpr double kTouching = 0.05;

int64_t cellKey(const Eigen::Vector3d& p, double cell) {
  const int64_t ix = static_cast<int64_t>(std::floor(p.x() / cell));
  const int64_t iy = static_cast<int64_t>(std::floor(p.y() / cell));
  return (ix << 32) ^ (iy & 0xffffffff);
}

// Appends the points of `add` not already present (at 5 cm) to `into`.
void unionPoints(std::vector<Eigen::Vector3d>* into, const std::vector<Eigen::Vector3d>& add) {
  constexpr double kDedupCell = 0.05;
  std::unordered_set<int64_t> seen;
  seen.reserve(into->size() + add.size());
  for (const auto& p : *into) seen.insert(cellKey(p, kDedupCell));
  for (const auto& p : add) {
    if (seen.insert(cellKey(p, kDedupCell)).second) into->push_back(p);
  }
}

void unionIds(std::vector<uint32_t>* into, const std::vector<uint32_t>& add) {
  into->insert(into->end(), add.begin(), add.end());
  std::sort(into->begin(), into->end());
  into->erase(std::unique(into->begin(), into->end()), into->end());
}

// True when the segments a-b and p-(p+s) cross (a-b's own ends excluded).
bool segmentCrosses(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p,
                    const Eigen::Vector2d& s) {
  const auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
    return u.x() * v.y() - u.y() * v.x();
  };
  const Eigen::Vector2d r = b - a;
  const double denom = cross(r, s);
  if (std::abs(denom) < 1e-9) return false;  // parallel: a bounding wall, not a separating one
  const double t = cross(p - a, s) / denom, u = cross(p - a, r) / denom;
  return t > 0.0 && t < 1.0 && u >= 0.0 && u <= 1.0;
}

// True when the segment a-b crosses a mapped wall (a wall stands between two views).
bool wallBetween(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                 const std::map<uint32_t, WallLandmark>& landmarks) {
  return std::any_of(landmarks.begin(), landmarks.end(), [&](const auto& entry) {
    const WallLandmark& w = entry.second;
    return segmentCrosses(a, b, w.endpoints[0], w.endpoints[1] - w.endpoints[0]);
  });
}

// True when the segment a-b passes through one of the doorways.
bool doorBetween(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                 const std::vector<Doorway>& doorways) {
  return std::any_of(doorways.begin(), doorways.end(),
                     [&](const Doorway& d) { return segmentCrosses(a, b, d.a, d.b - d.a); });
}

// Share of the smaller of two non-empty cell sets that lies in the other one.
double smallerShare(const std::unordered_set<int64_t>& a, const std::unordered_set<int64_t>& b) {
  const auto& small = a.size() < b.size() ? a : b;
  const auto& large = a.size() < b.size() ? b : a;
  size_t shared = 0;
  for (int64_t c : small) shared += large.count(c);
  return static_cast<double>(shared) / small.size();
}

}  // namespace

RoomNode MappedRoom::toNode() const {
  RoomNode n;
  n.id = id;
  n.kind = room.kind;
  n.center = room.center;
  n.wall_ids = room.wallIds();
  n.free_space.reserve(room.free_space.size());
  for (const auto& p : room.free_space) n.free_space.push_back(p.head<2>());
  n.keyframe_ids = room.keyframe_ids;
  return n;
}

RoomMap::RoomMap(const RoomMergingConfig& config) : config_(config) { config_.validate(); }

void RoomMap::clear() {
  rooms_.clear();
  wall_memo_.clear();
  next_id_ = 0;
}

std::unordered_set<int64_t> RoomMap::cellsOf(const std::vector<Eigen::Vector3d>& pts) const {
  std::unordered_set<int64_t> cells;
  cells.reserve(pts.size());
  for (const auto& p : pts) cells.insert(cellKey(p, config_.overlap_cell));
  return cells;
}

double RoomMap::axisDistance(const RoomObservation& a, const RoomObservation& b) {
  // Measured in the axes of `a` (the mapped room); b's axes agree up to the axes estimate noise.
  const Eigen::Vector2d delta = (a.center - b.center).head<2>();
  double dist = -1.0;
  if (a.hasXPair() && b.hasXPair()) dist = std::max(dist, std::abs(delta.dot(a.xAxis())));
  if (a.hasYPair() && b.hasYPair()) dist = std::max(dist, std::abs(delta.dot(a.yAxis())));
  return dist;
}

uint32_t RoomMap::create(const RoomObservation& observation) {
  MappedRoom& m = rooms_[next_id_];
  m.id = next_id_;
  m.room = observation;
  m.observations = 1;
  m.cells = cellsOf(observation.free_space);
  return next_id_++;
}

void RoomMap::mergeInto(MappedRoom* m, const RoomObservation& o, bool union_free_space,
                        const std::map<uint32_t, WallLandmark>& landmarks, RoomAssociation* out) {
  out->room_id = m->id;
  out->created = false;
  const auto obs_cells = cellsOf(o.free_space);
  // Walls: adopt a facing pair the mapped room lacks; tie differing walls (eq. 4).
  for (int pair = 0; pair < 2; ++pair) {
    const int lo = 2 * pair, hi = 2 * pair + 1;
    const bool mapped_has = m->room.walls[lo] >= 0 && m->room.walls[hi] >= 0;
    const bool obs_has = o.walls[lo] >= 0 && o.walls[hi] >= 0;
    if (!obs_has) continue;
    if (!mapped_has) {
      m->room.walls[lo] = o.walls[lo];
      m->room.walls[hi] = o.walls[hi];
      continue;
    }
    // Walls of the same category that are two landmarks of one wall are tied (eq. 4). Where the
    // two views chose different walls, the view with more free space decides.
    const bool obs_larger = obs_cells.size() > m->cells.size();
    bool replace = false;
    for (int c : {lo, hi}) {
      if (m->room.walls[c] == o.walls[c]) continue;
      if (sameWall(m->room.walls[c], o.walls[c])) {
        out->wall_to_wall.emplace_back(static_cast<uint32_t>(m->room.walls[c]),
                                       static_cast<uint32_t>(o.walls[c]));
      } else {
        replace = replace || obs_larger;
      }
    }
    if (replace) {
      out->wall_to_wall.clear();
      m->room.walls[lo] = o.walls[lo];
      m->room.walls[hi] = o.walls[hi];
    }
  }
  m->room.kind = m->room.hasXPair() && m->room.hasYPair() ? RoomKind::kRoom : RoomKind::kCorridor;
  if (union_free_space) {
    unionPoints(&m->room.free_space, o.free_space);
    m->cells.insert(obs_cells.begin(), obs_cells.end());
  } else {
    m->room.free_space = o.free_space;
    m->cells = obs_cells;
  }
  unionIds(&m->room.keyframe_ids, o.keyframe_ids);
  ++m->observations;
  recomputeRoomCenter(landmarks, &m->room);
}

RoomAssociation RoomMap::mergeOrCreate(MappedRoom* match, const RoomObservation& observation,
                                       bool union_free_space,
                                       const std::map<uint32_t, WallLandmark>& landmarks) {
  RoomAssociation out;
  if (match) {
    mergeInto(match, observation, union_free_space, landmarks, &out);
  } else {
    out.room_id = create(observation);
  }
  return out;
}

RoomAssociation RoomMap::addObservation(const RoomObservation& observation,
                                        const std::map<uint32_t, WallLandmark>& landmarks,
                                        const std::map<uint32_t, WallLandmark>* bounding) {
  remember(landmarks);
  const auto& separating = bounding ? *bounding : landmarks;
  const auto obs_cells = cellsOf(observation.free_space);
  MappedRoom* best = nullptr;
  double best_overlap = 0.0;
  for (auto& [id, m] : rooms_) {
    const double axis = axisDistance(m.room, observation);
    const bool aligned = axis >= 0.0 && axis <= config_.max_axis_distance;
    if (obs_cells.empty() || m.cells.empty()) continue;
    const double overlap = smallerShare(obs_cells, m.cells);
    // The same wall landmarks on every axis both define are the same room even where the two
    // views saw disjoint parts of its free space (a long corridor walked in pieces). Landmarks
    // of one wall plane (a wall broken by wide entrances) count when the views also touch:
    // rooms in a row share such planes but not their free space.
    const auto same_pair = [&](int lo, int hi, bool by_plane) {
      const auto& a = m.room.walls;
      const auto& b = observation.walls;
      if (a[lo] < 0 || a[hi] < 0 || b[lo] < 0 || b[hi] < 0) return true;  // axis not shared
      const auto same = [&](int c) { return a[c] == b[c] || (by_plane && sameWall(a[c], b[c])); };
      return same(lo) && same(hi);
    };
    // Views that are not both corridors must bound each other on both axes to merge apart:
    // rooms in a row share their front and back walls (one landmark across the doors), so one
    // shared pair alone would join neighbours that never touch.
    const bool corridors =
        m.room.kind == RoomKind::kCorridor && observation.kind == RoomKind::kCorridor;
    const bool apart_ok = corridors ||
                          (m.room.hasXPair() && m.room.hasYPair() && observation.hasXPair() &&
                           observation.hasYPair()) ||
                          overlap >= kTouching;
    // Two corridor views between landmarks of the same wall planes with no wall standing between
    // them are one corridor walked in pieces (its walls broken by doors); rooms in a row, which
    // also share such planes, have their partition wall between them.
    // (Only evaluated where it decides: the landmark scan is the costly part of the test.)
    const bool corridor_continues =
        corridors && overlap < kTouching &&
        !wallBetween(m.room.center.head<2>(), observation.center.head<2>(), landmarks);
    const bool same_walls = (apart_ok && same_pair(0, 1, false) && same_pair(2, 3, false)) ||
                            ((overlap >= kTouching || corridor_continues) &&
                             same_pair(0, 1, true) && same_pair(2, 3, true));
    // A view lying almost entirely inside the other is the same room whatever walls the
    // smaller one picked (a first, partial view of a room).
    const bool nested = sameOpenSpace(overlap, m.room, observation, separating) ||
                        closesAround(overlap, m.room, observation, landmarks, separating);
    const double score = same_walls && aligned ? std::max(overlap, 1.0) : overlap;
    const bool match = nested || (aligned && (overlap >= config_.min_overlap || same_walls));
    if (match && score > best_overlap) {
      best_overlap = score;
      best = &m;
    }
  }
  RoomAssociation out = mergeOrCreate(best, observation, /*union_free_space=*/true, landmarks);
  absorbNestedRooms(landmarks, separating, &out);
  return out;
}

std::optional<RoomAssociation> RoomMap::addUnbounded(
    const RoomObservation& region, const std::map<uint32_t, WallLandmark>& landmarks,
    const std::map<uint32_t, WallLandmark>& bounding, const std::vector<Doorway>& doorways) {
  remember(landmarks);
  // The region's cells with their 8 neighbours: a cell of a room among them is a contact.
  std::vector<std::array<int64_t, 9>> neighbourhoods;
  neighbourhoods.reserve(region.free_space.size());
  std::unordered_set<int64_t> seen;
  for (const auto& p : region.free_space) {
    if (!seen.insert(cellKey(p, config_.overlap_cell)).second) continue;
    std::array<int64_t, 9> keys;
    int k = 0;
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        keys[k++] =
            cellKey(p + Eigen::Vector3d(dx, dy, 0.0) * config_.overlap_cell, config_.overlap_cell);
      }
    }
    neighbourhoods.push_back(keys);
  }
  MappedRoom* best = nullptr;
  size_t best_contacts = kMinContactCells - 1;
  const std::vector<uint32_t> region_walls = region.wallIds();
  const Eigen::Vector2d region_centroid = region.freeSpaceCentroid();
  for (auto& [id, m] : rooms_) {
    // The room's walls must enclose the region (an office it touches through its door does not),
    // or the region lies along a face of its walls, on its side (an L-shaped hall's other wing).
    // A region with walls of its own (a hall's wide part, RoomSegmenter) joins four-wall rooms
    // only: a corridor's one pair flanks whatever lies between its walls, rooms behind them too.
    if (!region_walls.empty() && m.room.kind != RoomKind::kRoom) continue;
    // Either way, a region the room reaches only through a wall or a door is another space: the
    // aisle in front of an office whose desk hid its back wall lies between the office's side
    // walls, beyond its door.
    const Eigen::Vector2d room_centroid = m.room.freeSpaceCentroid();
    if (wallBetween(region_centroid, room_centroid, bounding) ||
        doorBetween(region_centroid, room_centroid, doorways)) {
      continue;
    }
    const bool shares_a_wall =
        std::any_of(region_walls.begin(), region_walls.end(), [&](uint32_t w) {
          return std::count(m.room.walls.begin(), m.room.walls.end(), static_cast<int>(w)) > 0;
        });
    if (!shares_a_wall &&
        shareWithinWalls(m.room, region.free_space, landmarks) < kMinEnclosedShare) {
      continue;
    }
    size_t contacts = 0;
    for (const auto& keys : neighbourhoods) {
      contacts += std::any_of(keys.begin(), keys.end(),
                              [&](int64_t key) { return m.cells.count(key) > 0; });
    }
    if (contacts > best_contacts) {
      best_contacts = contacts;
      best = &m;
    }
  }
  if (!best) return std::nullopt;
  RoomObservation joined = region;
  joined.walls = {-1, -1, -1, -1};  // the room keeps its own
  joined.axes_yaw = best->room.axes_yaw;
  RoomAssociation out;
  mergeInto(best, joined, /*union_free_space=*/true, landmarks, &out);
  absorbNestedRooms(landmarks, bounding, &out);
  return out;
}

bool RoomMap::sameOpenSpace(double overlap, const RoomObservation& a, const RoomObservation& b,
                            const std::map<uint32_t, WallLandmark>& bounding) const {
  if (overlap >= config_.nested_overlap) return true;
  // Views of an L- or T-shaped open-plan floor from different legs pick different walls and
  // centres yet share much of their free space with no wall between them.
  return overlap >= config_.open_overlap &&
         !wallBetween(a.center.head<2>(), b.center.head<2>(), bounding);
}

// Two corridor views on different axes that touch, each lying within the other's wall pair, are
// one four-wall room seen as two strips: the floor around a large table splits at it
// (legged_office's meeting room). Corridors that cross or meet at a corner reach beyond each
// other's walls.
bool RoomMap::closesAround(double overlap, const RoomObservation& a, const RoomObservation& b,
                           const std::map<uint32_t, WallLandmark>& landmarks,
                           const std::map<uint32_t, WallLandmark>& bounding) const {
  const bool crossed_axes = a.hasXPair() != b.hasXPair() && a.hasYPair() != b.hasYPair();
  return a.kind == RoomKind::kCorridor && b.kind == RoomKind::kCorridor && crossed_axes &&
         overlap >= kTouching &&
         shareWithinWalls(a, b.free_space, landmarks) >= kMinEnclosedShare &&
         shareWithinWalls(b, a.free_space, landmarks) >= kMinEnclosedShare &&
         !wallBetween(a.center.head<2>(), b.center.head<2>(), bounding);
}

bool RoomMap::spansSeparateRooms(const RoomObservation& observation,
                                 const std::map<uint32_t, WallLandmark>& landmarks) const {
  const auto obs_cells = cellsOf(observation.free_space);
  std::vector<const MappedRoom*> inside;
  for (const auto& [id, m] : rooms_) {
    if (!m.cells.empty() && m.cells.size() <= obs_cells.size() &&
        smallerShare(obs_cells, m.cells) >= config_.nested_overlap) {
      inside.push_back(&m);
    }
  }
  for (size_t i = 0; i < inside.size(); ++i) {
    for (size_t j = i + 1; j < inside.size(); ++j) {
      if (wallBetween(inside[i]->room.center.head<2>(), inside[j]->room.center.head<2>(),
                      landmarks)) {
        return true;
      }
    }
  }
  return false;
}

void RoomMap::absorbNestedRooms(const std::map<uint32_t, WallLandmark>& landmarks,
                                const std::map<uint32_t, WallLandmark>& bounding,
                                RoomAssociation* out) {
  for (bool merged = true; merged;) {
    merged = false;
    MappedRoom& grown = rooms_.at(out->room_id);
    for (auto& [id, other] : rooms_) {
      if (id == grown.id) continue;
      if (other.cells.empty() || grown.cells.empty()) continue;
      const double overlap = smallerShare(other.cells, grown.cells);
      if (!sameOpenSpace(overlap, other.room, grown.room, bounding) &&
          !closesAround(overlap, other.room, grown.room, landmarks, bounding)) {
        continue;
      }
      const bool other_smaller = other.cells.size() <= grown.cells.size();
      MappedRoom& keeper = other_smaller ? grown : other;
      const MappedRoom absorbed = std::move(other_smaller ? other : grown);  // erased below
      RoomAssociation merge;
      mergeInto(&keeper, absorbed.room, /*union_free_space=*/true, landmarks, &merge);
      keeper.observations += absorbed.observations - 1;
      out->wall_to_wall.insert(out->wall_to_wall.end(), merge.wall_to_wall.begin(),
                               merge.wall_to_wall.end());
      out->absorbed.push_back(absorbed.id);
      // The keeper existed before: what the observation grew is a re-detection of it.
      out->room_id = keeper.id;
      out->created = false;
      rooms_.erase(absorbed.id);
      merged = true;
      break;  // the map changed under the loop; test the grown room again
    }
  }
}

RoomAssociation RoomMap::addByCenterDistance(const RoomObservation& observation,
                                             const std::map<uint32_t, WallLandmark>& landmarks,
                                             double max_distance) {
  remember(landmarks);
  MappedRoom* best = nullptr;
  double best_dist = max_distance;
  for (auto& [id, m] : rooms_) {
    const double dist = (m.room.center - observation.center).head<2>().norm();
    if (dist <= best_dist) {
      best_dist = dist;
      best = &m;
    }
  }
  return mergeOrCreate(best, observation, /*union_free_space=*/false, landmarks);
}

bool RoomMap::sameWall(int a, int b) const {
  // Eq. 4 ties two landmarks of one wall; a wall the observation chose further away (a face of
  // furniture, a wall seen only in part) is another wall and gets no edge.
  const auto ma = wall_memo_.find(static_cast<uint32_t>(a));
  const auto mb = wall_memo_.find(static_cast<uint32_t>(b));
  if (ma == wall_memo_.end() || mb == wall_memo_.end()) return false;
  const double offset =
      std::abs(ma->second.normal.head<2>().dot(mb->second.midpoint - ma->second.midpoint));
  return offset <= config_.max_axis_distance;
}

void RoomMap::remember(const std::map<uint32_t, WallLandmark>& landmarks) {
  for (const auto& [id, w] : landmarks) wall_memo_[id] = {w.normal, w.midpoint()};
}

void RoomMap::refreshWalls(const std::map<uint32_t, WallLandmark>& landmarks) {
  constexpr double kMaxOffset = 0.3;      // plane distance at the old wall's middle [m]
  constexpr double kMinNormalDot = 0.94;  // about 20 deg
  for (auto& [rid, m] : rooms_) {
    for (int& w : m.room.walls) {
      if (w < 0 || landmarks.count(static_cast<uint32_t>(w))) continue;
      const auto memo = wall_memo_.find(static_cast<uint32_t>(w));
      if (memo == wall_memo_.end()) continue;
      int replacement = -1;
      double best = kMaxOffset;
      for (const auto& [id, lm] : landmarks) {
        if (lm.normal.dot(memo->second.normal) < kMinNormalDot) continue;
        const double off = std::abs(lm.normal.head<2>().dot(memo->second.midpoint) + lm.d);
        if (off <= best) {
          best = off;
          replacement = static_cast<int>(id);
        }
      }
      if (replacement >= 0) w = replacement;
    }
    recomputeRoomCenter(landmarks, &m.room);
  }
  remember(landmarks);
}

}  // namespace tacs
