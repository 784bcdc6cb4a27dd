#include "tacs_graphs/relocalization/prior_session.h"

#include <pcl/common/transforms.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "tacs_graphs/common/file_io.h"
#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/odometry/preprocess.h"

namespace tacs {

namespace {

constexpr double kPi = 3.14159265358979323846;

nlohmann::json poseJson(const Pose3& T) {
  const Eigen::Quaterniond q(T.rotation());
  return {
      T.translation().x(), T.translation().y(), T.translation().z(), q.x(), q.y(), q.z(), q.w()};
}

nlohmann::json roomJson(const std::optional<uint32_t>& room) {
  return room ? nlohmann::json(*room) : nlohmann::json(nullptr);
}

template <class Map>
uint32_t nextId(const Map& nodes) {
  return nodes.empty() ? 0 : nodes.rbegin()->first + 1;
}

/// The extent of a wall along its own direction (its ends projected on the horizontal line of
/// `ref`).
std::pair<double, double> spanAlong(const WallNode& w, const Eigen::Vector2d& direction) {
  const double a = w.endpoints[0].dot(direction), b = w.endpoints[1].dot(direction);
  return {std::min(a, b), std::max(a, b)};
}

}  // namespace

bool onOnePlane(const WallNode& a, const WallNode& b, double max_angle_deg, double max_offset_m) {
  if (a.is_wall != b.is_wall) return false;
  if (a.normal.dot(b.normal) < std::cos(max_angle_deg * kPi / 180.0)) return false;
  if (std::abs(a.d - b.d) > max_offset_m) return false;
  const Eigen::Vector2d direction = Eigen::Vector2d(-a.normal.y(), a.normal.x()).normalized();
  const auto [a0, a1] = spanAlong(a, direction);
  const auto [b0, b1] = spanAlong(b, direction);
  return std::min(a1, b1) - std::max(a0, b0) > -0.5;
}

namespace {

// A session wall (moved into the prior's frame) on a prior wall's plane.
bool samePlane(const WallNode& prior, const WallNode& session) {
  return onOnePlane(prior, session, 10.0, 0.3);
}

}  // namespace

PriorSession::PriorSession(PriorMap prior, PriorMode mode, const RelocalizationConfig& config)
    : prior_(std::make_unique<PriorMap>(std::move(prior))),
      mode_(mode),
      relocalizer_(std::make_unique<RoomRelocalizer>(*prior_, config)) {}

PointCloud PriorSession::sessionMap(const SceneGraph& session, const KeyframeClouds& clouds) const {
  return buildMapCloud(session, clouds, relocalizer_->config().cloud_voxel_m);
}

void PriorSession::tryRooms(const SceneGraph& session, const KeyframeClouds& clouds, double stamp,
                            double distance_m) {
  std::optional<PointCloud> map;  // built once, when a room is tried
  for (const auto& [id, room] : session.rooms) {
    const auto tried = tried_.find(id);
    if (tried != tried_.end() &&
        static_cast<double>(room.free_space.size()) < 1.5 * static_cast<double>(tried->second)) {
      continue;
    }
    tried_[id] = room.free_space.size();
    if (!map) map = sessionMap(session, clouds);
    if (book(relocalizer_->tryRoom(session, *map, id), stamp, distance_m)) return;
  }
}

bool PriorSession::book(const RelocalizationAttempt& attempt, double stamp, double distance_m) {
  last_attempt_m_ = distance_m;
  ++attempts_;
  log_.push_back({{"stamp", stamp},
                  {"distance_m", distance_m},
                  {"session_room", roomJson(attempt.session_room)},
                  {"hypotheses", attempt.hypotheses},
                  {"best_prior_room", attempt.best.prior_room},
                  {"best_score", attempt.best.score},
                  {"best_T_prior_session", poseJson(attempt.best.T_prior_session)},
                  {"runner_up_score", attempt.runner_up_score},
                  {"wall_points", attempt.wall_points},
                  {"result", attempt.localized ? "localized" : attempt.reason}});
  hypotheses_ += attempt.hypotheses;
  rejected_ += attempt.rejected;
  time_ms_ += attempt.time_ms;
  if (!attempt.localized) return false;
  first_ = FirstLocalization{stamp, distance_m, attempt};
  T_prior_session_ = attempt.best.T_prior_session;
  last_refined_score_ = attempt.best.score;
  return true;
}

void PriorSession::tryMap(const SceneGraph& session, const KeyframeClouds& clouds, double stamp,
                          double distance_m) {
  if (session.keyframes.empty()) return;
  const Eigen::Vector3d where = session.keyframes.rbegin()->second.position;  // the newest
  book(relocalizer_->tryMap(sessionMap(session, clouds), where), stamp, distance_m);
}

bool PriorSession::wantsMapAttempt(double distance_m) const {
  const double retry = relocalizer_->config().retry_distance_m;
  return !localized() && retry > 0.0 && distance_m - last_attempt_m_ >= retry;
}

void PriorSession::update(const SceneGraph& session, const KeyframeClouds& clouds, double stamp,
                          double distance_m) {
  if (!localized()) {
    tryRooms(session, clouds, stamp, distance_m);
    if (wantsMapAttempt(distance_m)) tryMap(session, clouds, stamp, distance_m);
  } else {
    // Placed: a new room refines the place against the prior's map (the session's map grew).
    bool new_room = false;
    for (const auto& [id, room] : session.rooms) {
      new_room |= tried_.emplace(id, room.free_space.size()).second;
    }
    if (new_room) refinePlace(session, clouds);
  }
  if (localized()) {
    room_pairs_ = pairRooms(session, prior_->graph, T_prior_session_,
                            relocalizer_->config().room_pair_overlap);
  }
}

void PriorSession::refinePlace(const SceneGraph& session, const KeyframeClouds& clouds) {
  Stopwatch watch;
  const PlaceHypothesis h = relocalizer_->refine(sessionMap(session, clouds), T_prior_session_);
  time_ms_ += watch.elapsedMs();
  const Pose3 step = T_prior_session_.inverse() * h.T_prior_session;
  // A refinement that fits worse, or jumps, is not taken: the place is kept.
  if (h.score >= relocalizer_->config().min_score &&
      step.translation().norm() <= relocalizer_->config().distinct_distance_m &&
      rotationAngleDeg(step) <= relocalizer_->config().distinct_angle_deg) {
    T_prior_session_ = h.T_prior_session;
    last_refined_score_ = h.score;
    ++refinements_;
  }
}

void PriorSession::finish(const SceneGraph& session, const KeyframeClouds& clouds, double stamp,
                          double distance_m) {
  if (!localized()) {
    tryRooms(session, clouds, stamp, distance_m);
    // A session that never tried a room still gets one whole-map attempt.
    if (!localized() && (wantsMapAttempt(distance_m) || attempts_ == 0)) {
      tryMap(session, clouds, stamp, distance_m);
    }
  } else {
    refinePlace(session, clouds);  // on the whole map
  }
  if (localized()) {
    room_pairs_ = pairRooms(session, prior_->graph, T_prior_session_,
                            relocalizer_->config().room_pair_overlap);
  }
}

SceneGraph PriorSession::outputGraph(const SceneGraph& session) const {
  if (!localized()) return session;
  if (mode_ == PriorMode::kLocalizeOnly) return prior_->graph;
  return mergeSceneGraphs(prior_->graph, session, T_prior_session_, room_pairs_);
}

nlohmann::json PriorSession::localizationJson() const {
  nlohmann::json j;
  j["status"] = localized() ? "localized" : "not_localized";
  j["mode"] = enumName(mode_);
  j["prior"] = prior_->dir;
  j["attempts"] = attempts_;
  j["hypotheses_verified"] = hypotheses_;
  j["rejected_hypotheses"] = rejected_;
  j["refinements"] = refinements_;
  j["time_ms"] = time_ms_;
  if (first_) {
    const RelocalizationAttempt& a = first_->attempt;
    j["first_localization"] = {{"stamp", first_->stamp},
                               {"distance_m", first_->distance_m},
                               {"session_room", roomJson(a.session_room)},
                               {"prior_room", a.best.prior_room},
                               {"score", a.best.score},
                               {"runner_up_score", a.runner_up_score},
                               {"T_prior_session", poseJson(a.best.T_prior_session)}};
    j["T_prior_session"] = poseJson(T_prior_session_);
    j["score"] = last_refined_score_;
  }
  nlohmann::json pairs = nlohmann::json::array();
  for (const auto& [session_id, prior_id] : room_pairs_) {
    pairs.push_back({{"session", session_id}, {"prior", prior_id}});
  }
  j["room_pairs"] = pairs;
  j["attempt_log"] = log_;
  return j;
}

void PriorSession::writeFiles(const std::string& dir, const SceneGraph& session) const {
  writeFileAtomically(dir + "/localization.json", localizationJson().dump(2) + "\n");
  if (!localized()) return;
  session.transformed(T_prior_session_).save(dir + "/session_graph.json");
  if (mode_ == PriorMode::kLocalizeOnly) {
    std::error_code ec;
    std::filesystem::copy_file(prior_->dir + "/scene_graph.json", dir + "/scene_graph.json",
                               std::filesystem::copy_options::overwrite_existing, ec);
    if (ec)
      throw std::runtime_error(dir + "/scene_graph.json: cannot copy the prior's: " + ec.message());
  } else {
    outputGraph(session).save(dir + "/scene_graph.json");
  }
}

bool PriorSession::writePriorFrameMap(const std::string& dir, const SceneGraph& session,
                                      const PointCloud& session_map, double voxel_m) const {
  if (!localized()) return false;
  ensureDirectory(dir);
  writeFiles(dir, session);
  PointCloud map = prior_->points;
  if (mode_ == PriorMode::kMerge) {
    PointCloud moved;
    pcl::transformPointCloud(session_map, moved, T_prior_session_.matrix().cast<float>());
    map = voxelDownsample(map + moved, voxel_m);
  }
  writePcdAtomically(dir + "/map.pcd", map);
  return true;
}

SceneGraph mergeSceneGraphs(const SceneGraph& prior, const SceneGraph& session,
                            const Pose3& T_prior_session,
                            const std::map<uint32_t, uint32_t>& room_pairs) {
  SceneGraph out = prior;
  const SceneGraph moved = session.transformed(T_prior_session);
  const uint32_t kf_base = nextId(prior.keyframes);
  uint32_t next_wall = nextId(prior.walls), next_room = nextId(prior.rooms);
  const auto keyframeId = [&](uint32_t id) { return kf_base + id; };

  std::map<uint32_t, uint32_t> wall_ids;
  for (const auto& [id, wall] : moved.walls) {
    const auto same = std::find_if(prior.walls.begin(), prior.walls.end(),
                                   [&](const auto& p) { return samePlane(p.second, wall); });
    if (same != prior.walls.end()) {
      wall_ids[id] = same->first;
      continue;
    }
    WallNode added = wall;
    added.id = next_wall++;
    wall_ids[id] = added.id;
    out.walls[added.id] = added;
  }
  std::map<uint32_t, uint32_t> room_ids;
  for (const auto& [id, room] : moved.rooms) {
    std::vector<uint32_t> walls, keyframes;
    for (uint32_t w : room.wall_ids) walls.push_back(wall_ids.at(w));
    for (uint32_t k : room.keyframe_ids) keyframes.push_back(keyframeId(k));
    const auto pair = room_pairs.find(id);
    if (pair != room_pairs.end() && out.rooms.count(pair->second)) {
      room_ids[id] = pair->second;
      RoomNode& known = out.rooms[pair->second];
      known.keyframe_ids.insert(known.keyframe_ids.end(), keyframes.begin(), keyframes.end());
      continue;
    }
    RoomNode added = room;
    added.id = next_room++;
    added.wall_ids = walls;
    added.keyframe_ids = keyframes;
    room_ids[id] = added.id;
    out.rooms[added.id] = added;
  }
  for (const auto& [id, kf] : moved.keyframes) {
    KeyframeNode added = kf;
    added.id = keyframeId(id);
    if (kf.room_id >= 0) {
      const auto it = room_ids.find(static_cast<uint32_t>(kf.room_id));
      added.room_id = it == room_ids.end() ? -1 : static_cast<int>(it->second);
    }
    out.keyframes[added.id] = added;
  }
  for (LoopEdge loop : moved.loops) {
    loop.from = keyframeId(loop.from);
    loop.to = keyframeId(loop.to);
    out.loops.push_back(loop);
  }
  return out;
}

}  // namespace tacs
