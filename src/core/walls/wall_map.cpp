#include "tacs_graphs/walls/wall_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tacs_graphs/common/config.h"

namespace tacs {

void WallAssociationConfig::validate() const {
  const std::string p = "walls.association.";
  requireConfig(max_normal_angle_deg > 0.0 && max_normal_angle_deg < 90.0,
                p + "max_normal_angle_deg", "must be in (0, 90)");
  requireConfig(max_plane_distance > 0.0, p + "max_plane_distance_m", "must be > 0");
  requireConfig(max_gap >= 0.0, p + "max_gap_m", "must be >= 0");
  requireConfig(min_wall_length >= 0.0, p + "min_wall_length_m", "must be >= 0");
  requireConfig(min_wall_observations >= 1, p + "min_wall_observations", "must be >= 1");
}

namespace {

// A cabinet, partition, pallet rack or machine stands at most this far in front of the wall
// behind it (m; the machine by the real hall's east opening stands 0.9-1.2 m before the wall), and
// a face seen reaching this much higher than another is another surface (m): the bounds of
// isSeenOver() and standsBeforeATallerWall().
constexpr double kMaxSlab = 1.25;
constexpr double kTopMargin = 0.5;

double midHeight(const WallLandmark& w) { return 0.5 * (w.z_min + w.z_max); }

// Re-projects a landmark's extent onto its current plane line, covering the given points.
void setExtent(WallLandmark* w, const std::vector<Eigen::Vector2d>& points) {
  const Eigen::Vector2d axis = wallAxis(w->normal);
  const double z = midHeight(*w);
  double t_min = std::numeric_limits<double>::infinity(), t_max = -t_min;
  Eigen::Vector2d lo = Eigen::Vector2d::Zero(), hi = lo;
  for (const auto& p : points) {
    const Eigen::Vector2d q = projectOntoWallLine(w->normal, w->d, p, z);
    const double t = axis.dot(q);
    if (t < t_min) {
      t_min = t;
      lo = q;
    }
    if (t > t_max) {
      t_max = t;
      hi = q;
    }
  }
  w->endpoints[0] = lo;
  w->endpoints[1] = hi;
}

// Distance between the two planes at the segments' midpoints (mean of both directions, m).
double planeGap(const WallLandmark& a, const WallLandmark& b) {
  return 0.5 * (std::abs(planeDistance(a.normal, a.d, b.midpoint(), midHeight(b))) +
                std::abs(planeDistance(b.normal, b.d, a.midpoint(), midHeight(a))));
}

// The extent of w along `axis` as (low, high) (m).
std::pair<double, double> extentOn(const Eigen::Vector2d& axis, const WallLandmark& w) {
  const double t0 = axis.dot(w.endpoints[0]), t1 = axis.dot(w.endpoints[1]);
  return {std::min(t0, t1), std::max(t0, t1)};
}

// Gap between the extents along a's wall axis (m); negative when they overlap.
double extentGap(const WallLandmark& a, const WallLandmark& b) {
  const Eigen::Vector2d axis = wallAxis(a.normal);
  const auto [a0, a1] = extentOn(axis, a);
  const auto [b0, b1] = extentOn(axis, b);
  return std::max(b0 - a1, a0 - b1);
}

// Plane distance when a and b pass the association gates, or a negative value.
double matchDistance(const WallLandmark& a, const WallLandmark& b,
                     const WallAssociationConfig& cfg) {
  if (a.normal.dot(b.normal) < std::cos(cfg.max_normal_angle_deg * M_PI / 180.0)) return -1.0;
  const double dist = planeGap(a, b);
  if (dist > cfg.max_plane_distance || extentGap(a, b) > cfg.max_gap) return -1.0;
  return dist;
}

// The candidate closest to `obs` (plane distance) among those passing the association gates, or
// null. `landmark_of` gives the landmark of an element of `candidates`.
// `separated(lm, obs)` vetoes a candidate.
template <class Candidates, class LandmarkOf, class Separated>
WallLandmark* closestMatch(Candidates& candidates, LandmarkOf landmark_of, const WallLandmark& obs,
                           const WallAssociationConfig& cfg, Separated separated) {
  WallLandmark* best = nullptr;
  double best_dist = std::numeric_limits<double>::infinity();
  for (auto& candidate : candidates) {
    WallLandmark& lm = landmark_of(candidate);
    const double dist = matchDistance(lm, obs, cfg);
    if (dist >= 0.0 && dist < best_dist && !separated(lm, obs)) {
      best_dist = dist;
      best = &lm;
    }
  }
  return best;
}

// Folds `other` into `target`: plane average (if enabled), extent and height union, counts.
void absorb(const WallLandmark& other, bool average_plane, WallLandmark* target) {
  std::vector<Eigen::Vector2d> ends = {target->endpoints[0], target->endpoints[1],
                                       other.endpoints[0], other.endpoints[1]};
  const double wt = static_cast<double>(std::max<uint64_t>(target->inliers, 1));
  const double wo = static_cast<double>(std::max<uint64_t>(other.inliers, 1));
  if (average_plane) {
    const Eigen::Vector3d pt(target->midpoint().x(), target->midpoint().y(), midHeight(*target));
    const Eigen::Vector3d po(other.midpoint().x(), other.midpoint().y(), midHeight(other));
    // Points on each plane near each segment, averaged with the normals.
    const Eigen::Vector3d qt = pt - target->normal * (target->normal.dot(pt) + target->d);
    const Eigen::Vector3d qo = po - other.normal * (other.normal.dot(po) + other.d);
    target->normal = (wt * target->normal + wo * other.normal).normalized();
    target->d = -target->normal.dot((wt * qt + wo * qo) / (wt + wo));
  }
  target->mean_top = (wt * target->mean_top + wo * other.mean_top) / (wt + wo);
  target->z_min = std::min(target->z_min, other.z_min);
  target->z_max = std::max(target->z_max, other.z_max);
  target->observations += other.observations;
  target->inliers += other.inliers;
  setExtent(target, ends);
}

WallLandmark landmarkFromObservation(const WallSegment& wall_in_map) {
  WallLandmark w;
  w.normal = wall_in_map.normal;
  w.d = wall_in_map.d;
  w.z_min = wall_in_map.z_min;
  w.z_max = wall_in_map.z_max;
  w.mean_top = wall_in_map.z_max;
  w.observations = 1;
  w.inliers = wall_in_map.inliers;
  setExtent(&w, {wall_in_map.endpoints[0], wall_in_map.endpoints[1]});
  return w;
}

}  // namespace

WallMap::WallMap(const WallAssociationConfig& config) : config_(config) { config_.validate(); }

std::vector<WallMap::Association> WallMap::associate(
    const std::vector<WallSegment>& observations_in_base, const Pose3& T_map_base) {
  std::vector<Association> out;
  out.reserve(observations_in_base.size());
  for (size_t i = 0; i < observations_in_base.size(); ++i) {
    const WallLandmark obs =
        landmarkFromObservation(transformWall(observations_in_base[i], T_map_base));
    WallLandmark* best = closestMatch(
        landmarks_, [](auto& entry) -> WallLandmark& { return entry.second; }, obs, config_,
        [this](const WallLandmark& a, const WallLandmark& b) { return separatedByAWall(a, b); });
    if (best) {
      absorb(obs, config_.average_planes, best);
      out.push_back({static_cast<int>(i), best->id, false});
    } else {
      WallLandmark created = obs;
      created.id = next_id_++;
      landmarks_.emplace(created.id, created);
      out.push_back({static_cast<int>(i), created.id, true});
    }
  }
  return out;
}

void WallMap::addSeenOver(const std::vector<WallSegment>& observations_in_base,
                          const Pose3& T_map_base) {
  for (const WallSegment& observation : observations_in_base) {
    const WallLandmark obs = landmarkFromObservation(transformWall(observation, T_map_base));
    WallLandmark* best = closestMatch(
        seen_over_, [](WallLandmark& s) -> WallLandmark& { return s; }, obs, config_,
        [](const WallLandmark&, const WallLandmark&) { return false; });
    if (best) {
      absorb(obs, config_.average_planes, best);
    } else {
      seen_over_.push_back(obs);
    }
  }
}

bool WallMap::isSeenOver(uint32_t id) const {
  const auto it = landmarks_.find(id);
  if (it == landmarks_.end() || seen_over_.empty()) return false;
  const WallLandmark& lm = it->second;
  const Eigen::Vector2d axis = wallAxis(lm.normal);
  const auto [l0, l1] = extentOn(axis, lm);
  if (l1 <= l0) return false;
  // Half the association distance: a surface seen over in front of a wall (a low cabinet against
  // it) is further from the wall's plane than that, the same cabinet seen twice is not.
  const double max_dist = 0.5 * config_.max_plane_distance;
  const double min_cos = std::cos(config_.max_normal_angle_deg * M_PI / 180.0);
  // How far behind the landmark's face a point lies (m).
  const auto depth = [&](const WallLandmark& w) {
    return -planeDistance(lm.normal, lm.d, w.midpoint(), midHeight(w));
  };
  // The back of a free-standing cabinet or partition seen over from the other side: a surface
  // facing away, at most kMaxSlab behind, with no face of another wall between the two (a low
  // cabinet in the next room stands in front of that room's face of the wall).
  // Other landmarks behind the face and overlapping it along the axis, with their depth: the
  // candidates for a face between the landmark and a back, gathered once for all surfaces.
  std::vector<std::pair<const WallLandmark*, double>> behind;
  for (const auto& [other_id, w] : landmarks_) {
    const double dw = depth(w);
    if (other_id != id && dw > 0.0 && dw < kMaxSlab && extentGap(lm, w) < 0.0) {
      behind.emplace_back(&w, dw);
    }
  }
  const auto back_of_slab = [&](const WallLandmark& s) {
    const double d = depth(s);
    if (s.normal.dot(lm.normal) > -min_cos || d <= 0.0 || d > kMaxSlab) return false;
    return std::none_of(behind.begin(), behind.end(), [&](const auto& b) {
      return b.first->normal.dot(s.normal) >= min_cos && b.second < d - max_dist;
    });
  };
  std::vector<std::pair<double, double>> covered;
  for (const WallLandmark& s : seen_over_) {
    // The landmark itself seen over tops out where the surface does; a surface whose top stays
    // well below the landmark's is a bench or a radiator in front of a wall seen reaching higher.
    const bool same_face = s.normal.dot(lm.normal) >= min_cos && planeGap(lm, s) <= max_dist &&
                           s.mean_top >= lm.mean_top - kTopMargin;
    if (!same_face && !back_of_slab(s)) continue;
    const auto [s_lo, s_hi] = extentOn(axis, s);
    const double s0 = std::max(l0, s_lo), s1 = std::min(l1, s_hi);
    if (s1 > s0) covered.emplace_back(s0, s1);
  }
  std::sort(covered.begin(), covered.end());
  double length = 0.0, end = l0;
  for (const auto& [s0, s1] : covered) {
    length += std::max(0.0, s1 - std::max(s0, end));
    end = std::max(end, s1);
  }
  return length >= 0.5 * (l1 - l0);
}

bool WallMap::standsBeforeATallerWall(uint32_t id) const {
  const auto it = landmarks_.find(id);
  if (it == landmarks_.end()) return false;
  const WallLandmark& lm = it->second;
  const Eigen::Vector2d axis = wallAxis(lm.normal);
  const auto [l0, l1] = extentOn(axis, lm);
  const double max_dist = 0.5 * config_.max_plane_distance;
  const double min_cos = std::cos(config_.max_normal_angle_deg * M_PI / 180.0);
  return std::any_of(landmarks_.begin(), landmarks_.end(), [&](const auto& entry) {
    const WallLandmark& w = entry.second;
    if (entry.first == id || w.normal.dot(lm.normal) < min_cos ||
        w.length() < config_.min_wall_length || w.mean_top < lm.mean_top + kTopMargin) {
      return false;
    }
    // How far the landmark stands in front of w's face.
    const double gap = planeDistance(w.normal, w.d, lm.midpoint(), midHeight(lm));
    if (gap <= max_dist || gap > kMaxSlab) return false;
    const auto [w0, w1] = extentOn(axis, w);
    return std::min(l1, w1) - std::max(l0, w0) >= 0.5 * (l1 - l0);
  });
}

bool WallMap::isWall(uint32_t id) const {
  const auto it = landmarks_.find(id);
  if (mirrored_walls_) return it != landmarks_.end() && mirrored_walls_->count(id) > 0;
  return it != landmarks_.end() && it->second.length() >= config_.min_wall_length &&
         it->second.observations >= static_cast<uint32_t>(config_.min_wall_observations) &&
         !isSeenOver(id) && !standsBeforeATallerWall(id);
}

bool WallMap::hasWallShape(uint32_t id) const {
  const auto it = landmarks_.find(id);
  if (it == landmarks_.end() || it->second.length() < config_.min_wall_length) return false;
  if (mirrored_walls_) {
    const bool observed_enough =
        it->second.observations >= static_cast<uint32_t>(config_.min_wall_observations);
    return mirrored_walls_->count(id) > 0 || !observed_enough;
  }
  return !isSeenOver(id) && !standsBeforeATallerWall(id);
}

std::map<uint32_t, WallLandmark> WallMap::walls() const {
  std::map<uint32_t, WallLandmark> out;
  for (const auto& [id, lm] : landmarks_) {
    if (isWall(id)) out.emplace_hint(out.end(), id, lm);
  }
  return out;
}

bool WallMap::separatedByAWall(const WallLandmark& a, const WallLandmark& b) const {
  if (config_.max_gap <= 0.0) return false;
  const Eigen::Vector2d axis = wallAxis(a.normal);
  const auto [a0, a1] = extentOn(axis, a);
  const auto [b0, b1] = extentOn(axis, b);
  const double gap_lo = b0 >= a1 ? a1 : b1, gap_hi = b0 >= a1 ? b0 : a0;
  if (gap_hi <= gap_lo) return false;  // the extents overlap
  // A wall meets the line from the front (the side both faces face) with one of its ends in the
  // gap; its own extent stops short of the line by about as much as the two pieces do.
  constexpr double kSlack = 0.1;  // [m]
  const double cos_45 = std::sqrt(0.5);
  for (const auto& [id, lm] : landmarks_) {
    if (&lm == &a || &lm == &b || std::abs(lm.normal.dot(a.normal)) > cos_45 ||
        lm.length() < config_.min_wall_length) {
      continue;
    }
    for (const Eigen::Vector2d& p : lm.endpoints) {
      const double in_front = planeDistance(a.normal, a.d, p, midHeight(a));
      const double t = axis.dot(p);
      if (in_front >= -kSlack && in_front <= config_.max_gap && t >= gap_lo - kSlack &&
          t <= gap_hi + kSlack) {
        return true;
      }
    }
  }
  return false;
}

std::vector<std::pair<uint32_t, uint32_t>> WallMap::mergeDuplicates() {
  // The first pair of landmarks that pass the association gates, or false.
  auto findPair = [this](uint32_t* a_id, uint32_t* b_id) {
    for (auto a = landmarks_.begin(); a != landmarks_.end(); ++a) {
      for (auto b = std::next(a); b != landmarks_.end(); ++b) {
        if (matchDistance(a->second, b->second, config_) < 0.0 ||
            separatedByAWall(a->second, b->second)) {
          continue;
        }
        *a_id = a->first;
        *b_id = b->first;
        return true;
      }
    }
    return false;
  };
  std::vector<std::pair<uint32_t, uint32_t>> merges;
  uint32_t a_id = 0, b_id = 0;
  while (findPair(&a_id, &b_id)) {
    // Keep the better observed landmark; on a tie the lower id (a).
    const bool keep_a = landmarks_.at(a_id).observations >= landmarks_.at(b_id).observations;
    const uint32_t kept_id = keep_a ? a_id : b_id, removed_id = keep_a ? b_id : a_id;
    absorb(landmarks_.at(removed_id), config_.average_planes, &landmarks_.at(kept_id));
    landmarks_.erase(removed_id);
    for (auto& m : merges) {
      if (m.second == removed_id) m.second = kept_id;  // earlier merges follow along
    }
    merges.emplace_back(removed_id, kept_id);
  }
  return merges;
}

void WallMap::updateLandmarkPlane(uint32_t id, const Eigen::Vector3d& normal, double d) {
  auto it = landmarks_.find(id);
  if (it == landmarks_.end() || normal.norm() < 1e-9) return;
  WallLandmark& w = it->second;
  const double scale = (normal.dot(w.normal) < 0.0 ? -1.0 : 1.0) / normal.norm();
  const std::vector<Eigen::Vector2d> ends = {w.endpoints[0], w.endpoints[1]};
  w.normal = normal * scale;
  w.d = d * scale;
  setExtent(&w, ends);
}

void WallMap::setLandmarks(std::map<uint32_t, WallLandmark> landmarks,
                           std::optional<std::set<uint32_t>> wall_ids) {
  landmarks_ = std::move(landmarks);
  mirrored_walls_ = std::move(wall_ids);
  next_id_ = landmarks_.empty() ? 0 : landmarks_.rbegin()->first + 1;
}

WallMap wallMapFromSceneGraph(const SceneGraph& graph,
                              const std::map<uint32_t, uint32_t>& observations,
                              const WallAssociationConfig& config) {
  std::map<uint32_t, WallLandmark> landmarks;
  std::set<uint32_t> wall_ids;
  for (const auto& [id, wall] : graph.walls) {
    if (wall.is_wall) wall_ids.insert(id);
    WallLandmark& lm = landmarks[id];
    lm.id = id;
    lm.normal = wall.normal.normalized();
    lm.d = wall.d;
    lm.endpoints[0] = wall.endpoints[0];
    lm.endpoints[1] = wall.endpoints[1];
    lm.z_min = wall.z_range[0];
    lm.z_max = wall.z_range[1];
    lm.mean_top = lm.z_max;
    const auto count = observations.find(id);
    lm.observations = count == observations.end() ? 1 : std::max<uint32_t>(1, count->second);
  }
  WallMap map(config);
  map.setLandmarks(std::move(landmarks), std::move(wall_ids));
  return map;
}

}  // namespace tacs
