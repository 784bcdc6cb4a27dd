#include "tacs_graphs/traversability/traversable_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tacs {

namespace {

// Ranking of observations of one place: traversable (connected to a robot's floor), then a known
// label, then observed before inferred, then the lowest variance.
bool betterObservation(const TravNode& a, const TravNode& b) {
  if (a.traversable != b.traversable) return a.traversable;
  const bool ka = a.label != TravLabel::kUnknown, kb = b.label != TravLabel::kUnknown;
  if (ka != kb) return ka;
  if (a.inferred != b.inferred) return !a.inferred;
  return a.variance < b.variance;
}

TravGraph withoutUnknown(const TravGraph& in) {
  TravGraph out;
  std::vector<int> index(in.nodes.size(), -1);
  for (size_t i = 0; i < in.nodes.size(); ++i) {
    if (in.nodes[i].label == TravLabel::kUnknown && !in.nodes[i].traversable) continue;
    index[i] = static_cast<int>(out.nodes.size());
    out.nodes.push_back(in.nodes[i]);
  }
  for (const auto& e : in.edges) {
    if (e.first < in.nodes.size() && e.second < in.nodes.size() && index[e.first] >= 0 &&
        index[e.second] >= 0) {
      out.edges.emplace_back(index[e.first], index[e.second]);
    }
  }
  out.root = in.root >= 0 && in.root < static_cast<int>(in.nodes.size()) ? index[in.root] : -1;
  return out;
}

// Depth-first flood fill from `start` over `adj`, marking `seen`; returns the sorted component.
std::vector<uint32_t> floodFill(const std::vector<std::vector<uint32_t>>& adj, uint32_t start,
                                std::vector<char>* seen) {
  std::vector<uint32_t> out, stack{start};
  (*seen)[start] = 1;
  while (!stack.empty()) {
    const uint32_t s = stack.back();
    stack.pop_back();
    out.push_back(s);
    for (uint32_t t : adj[s]) {
      if (!(*seen)[t]) {
        (*seen)[t] = 1;
        stack.push_back(t);
      }
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TraversableMap::TraversableMap(const TraversabilityConfig& config)
    : config_(config), retention_(config.map_retention) {
  config_.validate();
}

void TraversableMap::clear() {
  keyframes_.clear();
  retention_ = KeyframeRetention(config_.map_retention);
  rebuild();
}

void TraversableMap::insert(const TravGraph& graph_in_base, const Pose3& T_map_base,
                            uint32_t keyframe_id) {
  const bool replacing = keyframes_.count(keyframe_id) > 0;
  Keyframe& kf = keyframes_[keyframe_id];
  kf.T_map_base = T_map_base;
  kf.graph = withoutUnknown(graph_in_base);
  if (replacing) {
    rebuild();
    return;
  }
  merge(kf, keyframe_id);
  // A released keyframe's nodes stay merged until the next rebuild, which leaves them out: the
  // keyframes kept at its place saw the same surroundings.
  const auto position_of = [this](uint32_t k) -> Eigen::Vector3d {
    return keyframes_.at(k).T_map_base.translation();
  };
  if (const auto released = retention_.add(keyframe_id, position_of)) keyframes_.erase(*released);
}

void TraversableMap::updatePoses(const std::map<uint32_t, Pose3>& poses) {
  for (auto& [id, kf] : keyframes_) {
    const auto it = poses.find(id);
    if (it != poses.end()) kf.T_map_base = it->second;
  }
  rebuild();
}

void TraversableMap::rebuild() {
  graph_ = TravGraph{};
  stats_.clear();
  cells_.clear();
  edge_keys_.clear();
  for (const auto& [id, kf] : keyframes_) merge(kf, id);
}

uint32_t TraversableMap::findOrAdd(const TravNode& node, uint32_t keyframe_id) {
  const double r = config_.map_resolution;
  const int64_t ix = static_cast<int64_t>(std::floor(node.position.x() / r));
  const int64_t iy = static_cast<int64_t>(std::floor(node.position.y() / r));
  std::vector<uint32_t>& cell = cells_[cellKey(ix, iy)];
  int best = -1;
  double best_dz = config_.map_merge_height;
  for (uint32_t i : cell) {
    const double dz = std::abs(graph_.nodes[i].position.z() - node.position.z());
    if (dz <= best_dz) {
      best_dz = dz;
      best = static_cast<int>(i);
    }
  }
  if (best < 0) {
    best = static_cast<int>(graph_.nodes.size());
    graph_.nodes.push_back(node);
    stats_.push_back({0, keyframe_id});
    cell.push_back(static_cast<uint32_t>(best));
  } else {
    TravNode& m = graph_.nodes[best];
    const float clearance = std::min(m.clearance, node.clearance);
    const bool traversable = m.traversable || node.traversable;
    if (betterObservation(node, m)) m = node;
    m.clearance = clearance;
    m.traversable = traversable;
  }
  TravNode& m = graph_.nodes[best];
  m.safe = m.traversable && m.clearance >= config_.safe_clearance;
  stats_[best].observations++;
  stats_[best].last_keyframe = keyframe_id;
  return static_cast<uint32_t>(best);
}

void TraversableMap::merge(const Keyframe& kf, uint32_t keyframe_id) {
  std::vector<uint32_t> index(kf.graph.nodes.size());
  const Eigen::Matrix3d R = kf.T_map_base.linear();
  for (size_t i = 0; i < kf.graph.nodes.size(); ++i) {
    TravNode node = kf.graph.nodes[i];
    node.position = kf.T_map_base * node.position;
    node.normal = R * node.normal;
    index[i] = findOrAdd(node, keyframe_id);
  }
  for (const auto& e : kf.graph.edges) {
    uint32_t a = index[e.first], b = index[e.second];
    if (a == b) continue;
    if (a > b) std::swap(a, b);
    if (edge_keys_.insert((static_cast<uint64_t>(a) << 32) | b).second) {
      graph_.edges.emplace_back(a, b);
    }
  }
}

std::vector<uint32_t> TraversableMap::nodesWithin(const Eigen::Vector3d& center,
                                                  double radius) const {
  std::vector<uint32_t> out;
  const double r = config_.map_resolution;
  const int64_t x0 = static_cast<int64_t>(std::floor((center.x() - radius) / r));
  const int64_t x1 = static_cast<int64_t>(std::floor((center.x() + radius) / r));
  const int64_t y0 = static_cast<int64_t>(std::floor((center.y() - radius) / r));
  const int64_t y1 = static_cast<int64_t>(std::floor((center.y() + radius) / r));
  for (int64_t ix = x0; ix <= x1; ++ix) {
    for (int64_t iy = y0; iy <= y1; ++iy) {
      const auto it = cells_.find(cellKey(ix, iy));
      if (it == cells_.end()) continue;
      for (uint32_t i : it->second) {
        if ((graph_.nodes[i].position - center).head<2>().norm() <= radius) out.push_back(i);
      }
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::vector<uint32_t>> TraversableMap::adjacency(bool safe_only) const {
  std::vector<std::vector<uint32_t>> adj(graph_.nodes.size());
  for (const auto& e : graph_.edges) {
    if (keep(e.first, safe_only) && keep(e.second, safe_only)) {
      adj[e.first].push_back(e.second);
      adj[e.second].push_back(e.first);
    }
  }
  return adj;
}

bool TraversableMap::keep(uint32_t i, bool safe_only) const {
  return safe_only ? graph_.nodes[i].safe : graph_.nodes[i].traversable;
}

std::vector<std::vector<uint32_t>> TraversableMap::safeComponents() const {
  const auto adj = adjacency(true);
  std::vector<char> seen(graph_.nodes.size(), 0);
  std::vector<std::vector<uint32_t>> out;
  for (uint32_t s = 0; s < graph_.nodes.size(); ++s) {
    if (!seen[s] && keep(s, true)) out.push_back(floodFill(adj, s, &seen));
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const auto& a, const auto& b) { return a.size() > b.size(); });
  return out;
}

std::vector<uint32_t> TraversableMap::componentAt(const Eigen::Vector3d& position,
                                                  bool safe_only) const {
  int best = -1;
  double best_cost = std::numeric_limits<double>::infinity();
  for (uint32_t i : nodesWithin(position, 2.0 * config_.map_resolution)) {
    const TravNode& v = graph_.nodes[i];
    if (!keep(i, safe_only)) continue;
    // Nearest in height first (levels), then in the plane.
    const double cost =
        std::abs(v.position.z() - position.z()) * 10.0 + (v.position - position).head<2>().norm();
    if (cost < best_cost) {
      best_cost = cost;
      best = static_cast<int>(i);
    }
  }
  if (best < 0) return {};
  std::vector<char> seen(graph_.nodes.size(), 0);
  return floodFill(adjacency(safe_only), static_cast<uint32_t>(best), &seen);
}

}  // namespace tacs
