#include "tacs_graphs/rooms/tacs_free_space.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

#include "tacs_graphs/walls/wall_segment.h"

namespace tacs {

namespace {

// Union-find over node indices (path halving, union by index).
struct DisjointSets {
  std::vector<int> parent;
  explicit DisjointSets(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Proper or touching intersection of segments pq and ab.
bool segmentsIntersect(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& a,
                       const Eigen::Vector2d& b) {
  const double d1 = cross2(b - a, p - a), d2 = cross2(b - a, q - a);
  const double d3 = cross2(q - p, a - p), d4 = cross2(q - p, b - p);
  return ((d1 <= 0 && d2 >= 0) || (d1 >= 0 && d2 <= 0)) &&
         ((d3 <= 0 && d4 >= 0) || (d3 >= 0 && d4 <= 0));
}

}  // namespace

std::vector<Doorway> findDoorways(const std::map<uint32_t, WallLandmark>& landmarks,
                                  const TacsFreeSpaceConfig& config) {
  const double cos_max = std::cos(config.jamb_max_angle_deg * M_PI / 180.0);
  std::vector<Doorway> out;
  for (const auto& [id_a, a] : landmarks) {
    if (a.length() < config.min_jamb_length) continue;
    const Eigen::Vector2d axis = wallAxis(a.normal);
    const double end_a = (a.endpoints[1] - a.endpoints[0]).dot(axis);
    // Collinear pieces of the same facing, as intervals on a's axis (origin at a's first end).
    double next_start = std::numeric_limits<double>::infinity();
    const WallLandmark* jamb = nullptr;
    uint32_t jamb_id = 0;
    bool covered = false;
    for (const auto& [id_b, b] : landmarks) {
      if (id_b == id_a || a.normal.dot(b.normal) < cos_max) continue;
      const Eigen::Vector2d mid = 0.5 * (a.endpoints[1] + b.endpoints[0]);
      if (std::abs(a.normal.head<2>().dot(mid) + a.d) > config.jamb_max_offset ||
          std::abs(b.normal.head<2>().dot(mid) + b.d) > config.jamb_max_offset) {
        continue;
      }
      const double s = (b.endpoints[0] - a.endpoints[0]).dot(axis);
      const double e = (b.endpoints[1] - a.endpoints[0]).dot(axis);
      if (s < end_a + config.min_doorway_width && e > end_a) covered = true;  // no opening here
      if (s > end_a && s < next_start) {
        next_start = s;
        jamb = &b;
        jamb_id = id_b;
      }
    }
    if (covered || !jamb || jamb->length() < config.min_jamb_length) continue;
    const double width = next_start - end_a;
    if (width < config.min_doorway_width || width > config.max_doorway_width) continue;
    Doorway d;
    d.a = a.endpoints[1];
    d.b = jamb->endpoints[0];
    d.wall_a = id_a;
    d.wall_b = jamb_id;
    out.push_back(d);
  }
  return out;
}

TacsFreeSpace::TacsFreeSpace(const TacsFreeSpaceConfig& config) : config_(config) {
  config_.validate();
}

TacsFreeSpace::Labels TacsFreeSpace::labelRoomGraph(
    const TraversableMap& map, const std::map<uint32_t, WallLandmark>& landmarks) const {
  const TravGraph& g = map.graph();
  Labels labels;
  // Nodes near a doorway: only their edges need the crossing test.
  const std::vector<Doorway> doorways = findDoorways(landmarks, config_);
  labels.doorways = doorways.size();
  constexpr double kJambOverlap = 0.2;  // the cut reaches this far past the wall ends [m]
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> cuts;
  std::vector<std::vector<int>> near(g.nodes.size());
  for (size_t k = 0; k < doorways.size(); ++k) {
    const Doorway& d = doorways[k];
    const Eigen::Vector2d dir = (d.b - d.a).normalized();
    cuts.emplace_back(d.a - kJambOverlap * dir, d.b + kJambOverlap * dir);
    const Eigen::Vector2d mid = 0.5 * (d.a + d.b);
    const double radius = 0.5 * d.width() + kJambOverlap + 1.0;
    for (uint32_t i : map.nodesWithin(Eigen::Vector3d(mid.x(), mid.y(), 0.0), radius)) {
      near[i].push_back(static_cast<int>(k));
    }
  }
  DisjointSets sets(g.nodes.size());
  labels.edge_open.assign(g.edges.size(), 1);
  for (size_t e = 0; e < g.edges.size(); ++e) {
    const auto [a, b] = g.edges[e];
    for (int k : near[a]) {
      if (segmentsIntersect(g.nodes[a].position.head<2>(), g.nodes[b].position.head<2>(),
                            cuts[k].first, cuts[k].second)) {
        labels.edge_open[e] = 0;
        break;
      }
    }
    if (labels.edge_open[e] && g.nodes[a].safe && g.nodes[b].safe) {
      sets.unite(static_cast<int>(a), static_cast<int>(b));
    }
  }
  labels.label.assign(g.nodes.size(), -1);
  for (size_t i = 0; i < g.nodes.size(); ++i) {
    if (g.nodes[i].safe) labels.label[i] = sets.find(static_cast<int>(i));
  }
  return labels;
}

int TacsFreeSpace::labelAt(const TraversableMap& map, const Labels& labels,
                           const Eigen::Vector3d& p) const {
  int best = -1;
  double best_cost = std::numeric_limits<double>::infinity();
  for (uint32_t i : map.nodesWithin(p, config_.robot_search_radius)) {
    if (labels.label[i] < 0) continue;
    const Eigen::Vector3d& q = map.graph().nodes[i].position;
    // Nearest in height first (levels of a building), then in the plane.
    const double cost = 10.0 * std::abs(q.z() - p.z()) + (q - p).head<2>().norm();
    if (cost < best_cost) {
      best_cost = cost;
      best = labels.label[i];
    }
  }
  return best;
}

std::optional<FreeSpaceRegion> TacsFreeSpace::emit(const TraversableMap& map, const Labels& labels,
                                                   const std::vector<Accumulated>& keyframes) {
  // T_room (eq. 3): the union over the keyframes of T_inside, each evaluated on the current room
  // graph (doorways found since then are cut).
  FreeSpaceRegion region;
  const TravGraph& g = map.graph();
  std::vector<char> in_room(g.nodes.size(), 0);
  std::unordered_set<int> whole;  // components taken whole (local_radius = 0)
  std::unordered_map<int, std::vector<Eigen::Vector2d>> seeds;  // component -> keyframes in it
  for (const auto& a : keyframes) {
    region.keyframe_ids.push_back(a.keyframe_id);
    region.keyframe_positions.push_back(a.position);
    const int l = labelAt(map, labels, a.position);
    if (l < 0) continue;
    if (config_.local_radius <= 0.0) {
      whole.insert(l);
    } else {
      seeds[l].push_back(a.position.head<2>());
    }
  }
  // One pass over the nodes: in a component of the region and within the local reach of one of
  // its keyframes.
  const double r2 = config_.local_radius * config_.local_radius;
  for (size_t i = 0; i < g.nodes.size(); ++i) {
    const int l = labels.label[i];
    if (l < 0) continue;
    if (whole.count(l)) {
      in_room[i] = 1;
      continue;
    }
    const auto it = seeds.find(l);
    if (it == seeds.end()) continue;
    const Eigen::Vector2d p = g.nodes[i].position.head<2>();
    for (const auto& s : it->second) {
      if ((p - s).squaredNorm() <= r2) {
        in_room[i] = 1;
        break;
      }
    }
  }
  attachBorder(g, labels, &in_room);
  for (size_t i = 0; i < g.nodes.size(); ++i) {
    if (in_room[i]) region.points.push_back(g.nodes[i].position);
  }
  if (region.points.empty()) return std::nullopt;
  return region;
}

void TacsFreeSpace::attachBorder(const TravGraph& g, const Labels& labels,
                                 std::vector<char>* in_room) const {
  if (config_.border_distance <= 0.0) return;
  // Traversable nodes too close to obstacles to be safe: breadth-first from the room's safe
  // nodes over uncut edges, each reached node remembering the safe node it came from.
  std::vector<std::vector<uint32_t>> adj(g.nodes.size());
  for (size_t e = 0; e < g.edges.size(); ++e) {
    const auto [a, b] = g.edges[e];
    if (!labels.edge_open[e] || (labels.label[a] >= 0 && labels.label[b] >= 0)) continue;
    adj[a].push_back(b);
    adj[b].push_back(a);
  }
  std::vector<int> origin(g.nodes.size(), -1);
  std::vector<uint32_t> queue;
  for (uint32_t i = 0; i < g.nodes.size(); ++i) {
    if ((*in_room)[i]) {
      origin[i] = static_cast<int>(i);
      queue.push_back(i);
    }
  }
  for (size_t q = 0; q < queue.size(); ++q) {
    const uint32_t i = queue[q];
    for (uint32_t j : adj[i]) {
      if (origin[j] >= 0 || labels.label[j] >= 0 || !g.nodes[j].traversable) continue;
      const Eigen::Vector3d& o = g.nodes[origin[i]].position;
      if ((g.nodes[j].position - o).head<2>().norm() > config_.border_distance) continue;
      origin[j] = origin[i];
      (*in_room)[j] = 1;
      queue.push_back(j);
    }
  }
}

TacsFreeSpace::StepResult TacsFreeSpace::step(uint32_t keyframe_id,
                                              const Eigen::Vector3d& robot_position,
                                              const TraversableMap& map,
                                              const std::map<uint32_t, WallLandmark>& landmarks) {
  StepResult result;
  const Labels labels = labelRoomGraph(map, landmarks);
  result.doorways = labels.doorways;
  const int here = labelAt(map, labels, robot_position);
  if (here < 0) return result;  // in a doorway or a narrow passage: held (eq. 3)
  result.inside = true;
  result.inside_nodes =
      static_cast<size_t>(std::count(labels.label.begin(), labels.label.end(), here));
  // Accumulated keyframes the room graph now separates from the robot: it went through a
  // doorway, or a doorway it passed earlier has been mapped since (a door whose jambs are long on
  // its far side only). Each of their components is a finished region, in the order the robot
  // visited them; the keyframes in the robot's component go on accumulating.
  std::vector<std::pair<int, std::vector<Accumulated>>> apart;  // component -> its keyframes
  std::vector<Accumulated> staying;
  int previous = -1;
  for (const auto& a : accumulated_) {
    int l = labelAt(map, labels, a.position);
    if (l < 0) l = previous;  // held in a doorway: with the keyframes before it
    previous = l;
    if (l < 0 || l == here) {
      staying.push_back(a);
      continue;
    }
    auto it = std::find_if(apart.begin(), apart.end(), [l](const auto& c) { return c.first == l; });
    if (it == apart.end()) it = apart.insert(apart.end(), {l, {}});
    it->second.push_back(a);
  }
  for (const auto& [component, keyframes] : apart) {
    if (auto region = emit(map, labels, keyframes)) result.finished.push_back(std::move(*region));
  }
  accumulated_ = std::move(staying);
  accumulated_.push_back({keyframe_id, robot_position});
  if (static_cast<int>(accumulated_.size()) >= config_.max_keyframes_per_observation) {
    if (auto region = emit(map, labels, accumulated_)) {
      result.finished.push_back(std::move(*region));
    }
    accumulated_.clear();
  }
  return result;
}

std::optional<FreeSpaceRegion> TacsFreeSpace::flush(
    const TraversableMap& map, const std::map<uint32_t, WallLandmark>& landmarks) {
  if (accumulated_.empty()) return std::nullopt;
  auto region = emit(map, labelRoomGraph(map, landmarks), accumulated_);
  accumulated_.clear();
  return region;
}

}  // namespace tacs
