#include "tacs_graphs/loop_closure/loop_detector.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>

#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/loop_closure/room_partitions.h"
#include "tacs_graphs/odometry/preprocess.h"

namespace tacs {

namespace {

// GicpCloud covariances are plane-regularised, C = I - (1 - f) n n^T with f = kGicpPlaneVariance
// (gicp.h), so the normal needs no eigen decomposition: n n^T = (I - C) / (1 - f). A point with
// too few neighbours has C = I (trace 3) and no normal.
bool hasNormal(const Eigen::Matrix3d& C) { return C.trace() < 2.5; }
double squaredNormalZ(const Eigen::Matrix3d& C) {
  return (1.0 - C(2, 2)) / (1.0 - kGicpPlaneVariance);
}
double squaredPlaneDistance(const Eigen::Matrix3d& C, const Eigen::Vector3d& r) {
  return std::max(0.0, (r.squaredNorm() - r.dot(C * r)) / (1.0 - kGicpPlaneVariance));
}

// Fewer wall-like points than this cannot tell a right alignment from a wrong one.
constexpr size_t kMinScoredPoints = 30;

// Two registrations this close found the same pose (a few GICP iterations' step).
constexpr double kSamePoseTranslationM = 0.05;
constexpr double kSamePoseRotationDeg = 0.5;
bool settledOn(const Pose3& a, const Pose3& b) {
  const Pose3 d = a.inverse() * b;
  return d.translation().norm() < kSamePoseTranslationM &&
         rotationAngleDeg(d) < kSamePoseRotationDeg;
}

}  // namespace

const char* loopPathName(LoopPath path) {
  switch (path) {
    case LoopPath::kCoarse:
      return "coarse";
    case LoopPath::kFine:
      return "fine";
    case LoopPath::kDistance:
      return "distance";
  }
  return "?";
}

LoopDetector::LoopDetector(const LoopClosureConfig& config)
    : config_(config), retention_(config.cloud_retention) {
  config_.validate();
}

void LoopDetector::addKeyframe(uint32_t id, double stamp, const Pose3& T_map_base,
                               const PointCloud& cloud) {
  const LoopRegistrationConfig& rc = config_.registration;
  Keyframe kf;
  kf.stamp = stamp;
  kf.T_map_base = T_map_base;
  if (any_added_ && keyframes_.count(last_added_)) {
    const Keyframe& prev = keyframes_.at(last_added_);
    kf.accum_distance =
        prev.accum_distance + (T_map_base.translation() - prev.T_map_base.translation()).norm();
  }
  kf.cloud = rc.keyframe_voxel_m > 0.0
                 ? GicpCloud::build(voxelDownsample(cloud, rc.keyframe_voxel_m), rc.k_neighbors,
                                    rc.num_threads)
                 : GicpCloud::build(cloud, rc.k_neighbors, rc.num_threads);
  const double max_nz_sq = rc.score_max_normal_z * rc.score_max_normal_z;
  const auto& covs = kf.cloud->covariances();
  for (size_t i = 0; i < covs.size(); ++i) {
    if (hasNormal(covs[i]) && squaredNormalZ(covs[i]) <= max_nz_sq) {
      kf.scored_points.push_back(static_cast<uint32_t>(i));
    }
  }
  const bool is_new = keyframes_.count(id) == 0;
  keyframes_[id] = std::move(kf);
  last_added_ = id;
  any_added_ = true;
  if (!is_new) return;
  const auto position_of = [this](uint32_t k) -> Eigen::Vector3d {
    return keyframes_.at(k).T_map_base.translation();
  };
  if (const auto released = retention_.add(id, position_of)) {
    Keyframe& old = keyframes_.at(*released);
    old.cloud.reset();
    std::vector<uint32_t>().swap(old.scored_points);
  }
}

void LoopDetector::updatePoses(const std::map<uint32_t, Pose3>& T_map_base) {
  for (const auto& [id, pose] : T_map_base) {
    auto it = keyframes_.find(id);
    if (it != keyframes_.end()) it->second.T_map_base = pose;
  }
}

double LoopDetector::accumulatedDistance(uint32_t id) const {
  auto it = keyframes_.find(id);
  return it == keyframes_.end() ? 0.0 : it->second.accum_distance;
}

double LoopDetector::matchScore(uint32_t candidate_id, uint32_t query_id,
                                const Pose3& T_candidate_query) const {
  const Keyframe& cand = keyframes_.at(candidate_id);
  const Keyframe& query = keyframes_.at(query_id);
  if (query.scored_points.size() < kMinScoredPoints || cand.cloud->empty()) return 0.0;
  const LoopRegistrationConfig& rc = config_.registration;
  const double search_sq = rc.score_search_radius_m * rc.score_search_radius_m;
  const double plane_sq = rc.score_plane_distance_m * rc.score_plane_distance_m;
  const auto& q_points = query.cloud->points();
  const auto& c_points = cand.cloud->points();
  const auto& c_covs = cand.cloud->covariances();
  size_t overlap = 0, matched = 0;
  for (uint32_t i : query.scored_points) {
    const Eigen::Vector3d p = T_candidate_query * q_points[i];
    double dist_sq = 0.0;
    const int64_t j = cand.cloud->nearest(p, search_sq, &dist_sq);
    if (j < 0) continue;  // outside what the candidate saw: neither evidence for nor against
    ++overlap;
    const Eigen::Vector3d r = p - c_points[j];
    // A match lies on the candidate's local surface; a point of a wall shifted along its own
    // plane still matches, one of a perpendicular wall does not.
    const double d_sq = hasNormal(c_covs[j]) ? squaredPlaneDistance(c_covs[j], r) : dist_sq;
    if (d_sq <= plane_sq) ++matched;
  }
  // Scored over the overlap, so two views of a room from 5 m apart (each seeing walls the other
  // does not) score as high as close views when aligned; an alignment that pushes most of the
  // query out of the candidate's view cannot win by a small overlap.
  const double scored = static_cast<double>(query.scored_points.size());
  return static_cast<double>(matched) /
         std::max(static_cast<double>(overlap), rc.score_min_overlap * scored);
}

GicpConfig LoopDetector::gicpConfig(double gate_m, bool robust) const {
  GicpConfig gc;
  gc.k_neighbors = config_.registration.k_neighbors;
  gc.max_iterations = config_.registration.max_iterations;
  gc.num_threads = config_.registration.num_threads;
  gc.max_correspondence_distance_m = gate_m;
  if (robust) gc.robust_plane_distance_m = config_.registration.robust_plane_distance_m;
  return gc;
}

LoopDetector::Registration LoopDetector::registerPair(uint32_t candidate, uint32_t query,
                                                      const Pose3& guess, const GicpConfig& gc,
                                                      bool score) const {
  Gicp gicp(gc);
  gicp.setTarget(keyframes_.at(candidate).cloud);
  gicp.setSource(keyframes_.at(query).cloud);
  Registration r;
  r.candidate = candidate;
  r.gicp = gicp.align(guess);
  if (score) r.score = matchScore(candidate, query, r.gicp.T_target_source);
  return r;
}

GicpCloud::ConstPtr LoopDetector::submap(uint32_t center, uint32_t other) const {
  const LoopRegistrationConfig& rc = config_.registration;
  const double half = 0.5 * rc.submap_length_m;
  const auto center_it = keyframes_.find(center);
  const double along = center_it->second.accum_distance;
  const double other_along = keyframes_.at(other).accum_distance;
  const Pose3 T_center_map = center_it->second.T_map_base.inverse();
  PointCloud merged;
  merged.points.reserve(8 * center_it->second.cloud->points().size());
  const auto add = [&](const Keyframe& kf) {
    const Eigen::Affine3d T = T_center_map * kf.T_map_base;
    for (const Eigen::Vector3d& p : kf.cloud->points()) {
      pcl::PointXYZI q;
      q.getVector3fMap() = (T * p).cast<float>();
      q.intensity = 0.0f;
      merged.points.push_back(q);
    }
  };
  add(center_it->second);
  size_t neighbours = 0;
  // Ids are in arrival order, so travel grows with the id: walk out both ways from the center.
  const auto visit = [&](auto begin, auto end) {
    for (auto it = begin; it != end; ++it) {
      const double d = std::abs(it->second.accum_distance - along);
      if (d > half) break;
      if (!it->second.cloud || d >= std::abs(it->second.accum_distance - other_along)) continue;
      add(it->second);
      ++neighbours;
    }
  };
  visit(std::next(center_it), keyframes_.end());
  visit(std::make_reverse_iterator(center_it), keyframes_.rend());
  if (neighbours == 0) return nullptr;
  return GicpCloud::build(voxelDownsample(merged, rc.submap_voxel_m), rc.k_neighbors,
                          rc.num_threads);
}

LoopClosure LoopDetector::makeLoop(const Registration& r, uint32_t query, LoopPath path,
                                   LoopDetection* detection) const {
  LoopClosure loop;
  loop.from = r.candidate;
  loop.to = query;
  loop.T_from_to = r.gicp.T_target_source;
  loop.score = r.score;
  loop.fitness = r.gicp.fitness;
  loop.path = path;
  // The information is taken (and a submap refinement runs) under the narrow (coarse) gate,
  // whatever gate found the pair, so loops from every path weigh alike in the graph.
  Gicp gicp(gicpConfig(config_.cosg.coarse_correspondence_m, true));
  gicp.setTarget(keyframes_.at(r.candidate).cloud);
  gicp.setSource(keyframes_.at(query).cloud);
  if (config_.registration.submap_length_m > 0.0) {
    const GicpCloud::ConstPtr target = submap(r.candidate, query);
    const GicpCloud::ConstPtr source = submap(query, r.candidate);
    if (target) gicp.setTarget(target);
    if (source) gicp.setSource(source);
    if (target || source) {
      const GicpResult refined = gicp.align(loop.T_from_to);
      ++detection->registrations;
      if (refined.inliers > 0) {
        loop.T_from_to = refined.T_target_source;
        loop.fitness = refined.fitness;
      }
    }
  }
  // Roll and pitch damped by tilt_information_scale (loop_closure_config.h): S H S stays positive
  // definite and scales their diagonal entries by the factor.
  Eigen::Matrix<double, 6, 1> s = Eigen::Matrix<double, 6, 1>::Ones();
  s(3) = s(4) = std::sqrt(config_.registration.tilt_information_scale);
  loop.information = config_.registration.information_scale * s.asDiagonal() *
                     gicp.evaluate(loop.T_from_to).information * s.asDiagonal();
  return loop;
}

bool LoopDetector::isRecent(const Keyframe& candidate, uint32_t candidate_id, const Keyframe& query,
                            uint32_t query_id) const {
  const int64_t id_gap =
      std::abs(static_cast<int64_t>(query_id) - static_cast<int64_t>(candidate_id));
  return id_gap < config_.cosg.min_id_separation ||
         std::abs(query.stamp - candidate.stamp) < config_.cosg.min_time_separation_s;
}

bool LoopDetector::soonAfterLastLoop(const Keyframe& query, double interval_m) const {
  return last_loop_accum_ >= 0.0 && query.accum_distance - last_loop_accum_ < interval_m;
}

void LoopDetector::finish(LoopDetection* detection, double elapsed_ms) {
  detection->time_ms = elapsed_ms;
  // Every loop of a detection has the same query.
  if (!detection->loops.empty()) {
    last_loop_accum_ = keyframes_.at(detection->loops.front().to).accum_distance;
  }
  ++stats_.detections;
  stats_.registrations += detection->registrations;
  stats_.total_ms += elapsed_ms;
  for (const LoopClosure& loop : detection->loops) {
    if (loop.path == LoopPath::kCoarse) ++stats_.coarse_loops;
    if (loop.path == LoopPath::kFine) ++stats_.fine_loops;
    if (loop.path == LoopPath::kDistance) ++stats_.distance_loops;
  }
}

LoopDetection LoopDetector::skipped(const std::string& why, const Stopwatch& watch) {
  LoopDetection det;
  det.skipped = why;
  finish(&det, watch.elapsedMs());
  return det;
}

LoopDetection LoopDetector::detectInRoom(uint32_t query_id,
                                         const std::vector<uint32_t>& room_keyframe_ids) {
  Stopwatch watch;
  auto query_it = keyframes_.find(query_id);
  if (query_it == keyframes_.end()) return skipped("unknown query keyframe", watch);
  if (!query_it->second.cloud) return skipped("the query keyframe's cloud was released", watch);
  const Keyframe& query = query_it->second;
  const CosgLoopConfig& cc = config_.cosg;
  if (soonAfterLastLoop(query, cc.min_loop_interval_m)) {
    return skipped("within min_loop_interval_m of the last loop", watch);
  }
  // The room's other keyframes: their estimates define the room's extent and partitions.
  std::vector<uint32_t> room;
  std::vector<Eigen::Vector2d> positions;
  for (uint32_t id : std::set<uint32_t>(room_keyframe_ids.begin(), room_keyframe_ids.end())) {
    auto it = keyframes_.find(id);
    if (id == query_id || it == keyframes_.end()) continue;
    room.push_back(id);
    positions.push_back(it->second.T_map_base.translation().head<2>());
  }
  if (room.empty()) return skipped("the room has no other known keyframe", watch);
  LoopDetection det;
  const RoomPartitions parts =
      partitionRoom(positions, query.T_map_base.translation().head<2>(), cc.partition_length_m);
  det.partitions = static_cast<int>(parts.centers.size());
  det.searched_partitions = parts.selected;
  const std::vector<Registration> coarse = coarsePath(query_id, room, parts, &det);
  if (det.loops.empty() && cc.max_fine_candidates > 0) finePath(query_id, coarse, &det);
  finish(&det, watch.elapsedMs());
  return det;
}

std::vector<LoopDetector::Registration> LoopDetector::coarsePath(uint32_t query_id,
                                                                 const std::vector<uint32_t>& room,
                                                                 const RoomPartitions& parts,
                                                                 LoopDetection* det) {
  // Fig. 5(b), partitions nearest first: register the nearest candidates of each from the
  // estimates; a partition's best pair is a loop when it reaches S_coarse, unless its candidate
  // lies within L_part along the path of an accepted loop's candidate: that would tie the query
  // to the same stretch of the earlier visit again. A partition whose candidates all lie there
  // is not registered at all (one room passed in one go gives one loop, not two).
  const CosgLoopConfig& cc = config_.cosg;
  const Keyframe& query = keyframes_.at(query_id);
  const Eigen::Vector3d q_pos = query.T_map_base.translation();
  const auto repeats_loop = [&](uint32_t candidate) {
    const double along = keyframes_.at(candidate).accum_distance;
    return std::any_of(det->loops.begin(), det->loops.end(), [&](const LoopClosure& loop) {
      return std::abs(keyframes_.at(loop.from).accum_distance - along) < cc.partition_length_m;
    });
  };
  const GicpConfig coarse_gicp = gicpConfig(cc.coarse_correspondence_m, true);
  std::vector<Registration> all;
  for (int partition : parts.selected) {
    std::vector<std::pair<double, uint32_t>> near;  // (distance, id)
    for (size_t i = 0; i < room.size(); ++i) {
      if (parts.index_of[i] != partition) continue;
      const Keyframe& cand = keyframes_.at(room[i]);
      if (!cand.cloud || isRecent(cand, room[i], query, query_id)) continue;
      const double d = (cand.T_map_base.translation() - q_pos).norm();
      if (d <= cc.d_loop_m) near.emplace_back(d, room[i]);
    }
    std::sort(near.begin(), near.end());
    for (const auto& [d, id] : near) det->candidates.push_back(id);
    near.resize(std::min(near.size(), static_cast<size_t>(cc.max_candidates_per_partition)));
    if (std::all_of(near.begin(), near.end(),
                    [&](const auto& n) { return repeats_loop(n.second); })) {
      continue;
    }
    const size_t first = all.size();
    for (const auto& [d, id] : near) {
      const Pose3 guess = keyframes_.at(id).T_map_base.inverse() * query.T_map_base;
      all.push_back(registerPair(id, query_id, guess, coarse_gicp));
      det->registered.push_back(id);
      det->coarse_scores.push_back(all.back().score);
      ++det->registrations;
    }
    auto best = std::max_element(all.begin() + first, all.end(),
                                 [](const auto& a, const auto& b) { return a.score < b.score; });
    if (best != all.end() && best->score >= cc.s_coarse && !repeats_loop(best->candidate)) {
      det->loops.push_back(makeLoop(*best, query_id, LoopPath::kCoarse, det));
    }
  }
  std::sort(det->loops.begin(), det->loops.end(),
            [](const LoopClosure& a, const LoopClosure& b) { return a.score > b.score; });
  return all;
}

void LoopDetector::finePath(uint32_t query_id, const std::vector<Registration>& coarse,
                            LoopDetection* det) {
  // No pair reached S_coarse, typically because the estimates are too far off for the narrow
  // gate. Weaker matches reaching S_fine are re-registered from the estimate with gates
  // shrinking stage by stage (coarse-to-fine); the refined pose must still earn S_coarse, as a
  // wide gate can also settle on a wrong but locally consistent pose.
  const CosgLoopConfig& cc = config_.cosg;
  const Keyframe& query = keyframes_.at(query_id);
  std::vector<const Registration*> weak;
  for (const Registration& r : coarse) {
    if (r.score >= cc.s_fine) weak.push_back(&r);
  }
  std::sort(weak.begin(), weak.end(), [](auto a, auto b) { return a->score > b->score; });
  if (weak.size() > static_cast<size_t>(cc.max_fine_candidates)) {
    weak.resize(cc.max_fine_candidates);
  }
  std::optional<Registration> best_fine;
  for (const Registration* w : weak) {
    Pose3 pose = keyframes_.at(w->candidate).T_map_base.inverse() * query.T_map_base;
    Registration refined;
    const auto& schedule = cc.fine_correspondence_schedule_m;
    for (size_t stage = 0; stage < schedule.size(); ++stage) {
      const bool last = stage + 1 == schedule.size();
      refined =
          registerPair(w->candidate, query_id, pose, gicpConfig(schedule[stage], false), last);
      pose = refined.gicp.T_target_source;
      ++det->registrations;
    }
    det->refined.push_back(refined.candidate);
    det->refined_scores.push_back(refined.score);
    if (!best_fine || refined.score > best_fine->score) best_fine = refined;
    // The wide gates came back to the coarse pose: the estimate was right and the scene scores
    // low (clutter), so the weaker matches, seen from the same estimate, would only repeat that.
    if (settledOn(refined.gicp.T_target_source, w->gicp.T_target_source)) break;
  }
  if (best_fine && best_fine->score >= cc.s_coarse) {
    det->loops.push_back(makeLoop(*best_fine, query_id, LoopPath::kFine, det));
  }
}

uint32_t cosgQueryKeyframe(const std::vector<uint32_t>& room_keyframe_ids, uint32_t fallback) {
  if (room_keyframe_ids.empty()) return fallback;
  return *std::max_element(room_keyframe_ids.begin(), room_keyframe_ids.end());
}

}  // namespace tacs
