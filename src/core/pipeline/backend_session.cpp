#include "tacs_graphs/pipeline/backend_session.h"

#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "tacs_graphs/common/file_io.h"
#include "tacs_graphs/common/trajectory_io.h"
#include "tacs_graphs/rooms/room_bounds.h"

namespace tacs {
namespace {

nlohmann::json poseToJson(const Pose3& T) {
  const Eigen::Quaterniond q(T.rotation());
  const Eigen::Vector3d t = T.translation();
  return {t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()};
}

Pose3 poseFromJson(const nlohmann::json& j) {
  const std::vector<double> v = j.get<std::vector<double>>();
  if (v.size() != 7) throw std::runtime_error("pose needs 7 numbers");
  Pose3 T = Pose3::Identity();
  T.translation() << v[0], v[1], v[2];
  T.linear() = Eigen::Quaterniond(v[6], v[3], v[4], v[5]).normalized().toRotationMatrix();
  return T;
}

nlohmann::json matrixToJson(const Eigen::Matrix<double, 6, 6>& m) {
  std::vector<double> v(36);
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) v[6 * r + c] = m(r, c);
  return v;
}

Eigen::Matrix<double, 6, 6> matrixFromJson(const nlohmann::json& j) {
  const std::vector<double> v = j.get<std::vector<double>>();
  if (v.size() != 36) throw std::runtime_error("information needs 36 numbers");
  Eigen::Matrix<double, 6, 6> m;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) m(r, c) = v[6 * r + c];
  return m;
}

nlohmann::json wallToJson(const WallSegment& w) {
  return {{"normal", {w.normal.x(), w.normal.y(), w.normal.z()}},
          {"d", w.d},
          {"inliers", w.inliers},
          {"endpoints",
           {{w.endpoints[0].x(), w.endpoints[0].y()}, {w.endpoints[1].x(), w.endpoints[1].y()}}},
          {"z_range", {w.z_min, w.z_max}}};
}

WallSegment wallFromJson(const nlohmann::json& j) {
  WallSegment w;
  const auto n = j.at("normal").get<std::vector<double>>();
  w.normal = Eigen::Vector3d(n.at(0), n.at(1), n.at(2));
  w.d = j.at("d").get<double>();
  w.inliers = j.at("inliers").get<uint32_t>();
  for (int i = 0; i < 2; ++i) {
    const auto e = j.at("endpoints").at(i).get<std::vector<double>>();
    w.endpoints[i] = Eigen::Vector2d(e.at(0), e.at(1));
  }
  w.z_min = j.at("z_range").at(0).get<double>();
  w.z_max = j.at("z_range").at(1).get<double>();
  return w;
}

// The mapped room as the room segmenter sent it (its free space in 3D, wall categories kept).
nlohmann::json roomToJson(const MappedRoom& room) {
  const RoomObservation& r = room.room;
  nlohmann::json free_space = nlohmann::json::array();
  for (const auto& p : r.free_space) free_space.push_back({p.x(), p.y(), p.z()});
  return {{"id", room.id},
          {"kind", roomKindName(r.kind)},
          {"walls", r.walls},
          {"center", {r.center.x(), r.center.y(), r.center.z()}},
          {"axes_yaw", r.axes_yaw},
          {"free_space", free_space},
          {"keyframe_ids", r.keyframe_ids},
          {"observations", room.observations}};
}

MappedRoom roomFromJson(const nlohmann::json& j) {
  MappedRoom room;
  room.id = j.at("id").get<uint32_t>();
  RoomObservation& r = room.room;
  r.kind = j.at("kind").get<std::string>() == "corridor" ? RoomKind::kCorridor : RoomKind::kRoom;
  r.walls = j.at("walls").get<std::array<int, 4>>();
  const auto c = j.at("center").get<std::vector<double>>();
  r.center = Eigen::Vector3d(c.at(0), c.at(1), c.at(2));
  r.axes_yaw = j.at("axes_yaw").get<double>();
  for (const auto& p : j.at("free_space")) {
    r.free_space.emplace_back(p.at(0).get<double>(), p.at(1).get<double>(), p.at(2).get<double>());
  }
  r.keyframe_ids = j.at("keyframe_ids").get<std::vector<uint32_t>>();
  room.observations = j.at("observations").get<uint32_t>();
  return room;
}

}  // namespace

BackendSession::BackendSession(const PipelineConfig& config, const BackendSessionOptions& options)
    : config_(config),
      options_(options),
      backend_(config.backend, config.walls.association),
      clouds_(config.map_export.cloud_retention),
      sensor_in_base_(config.frames.baseToSensor().translation()) {}

BackendSession::Outcome BackendSession::addKeyframe(uint32_t id, double stamp,
                                                    const Pose3& T_odom_base,
                                                    const Matrix6d& information,
                                                    const PointCloud::ConstPtr& cloud) {
  if (backend_.hasKeyframe(id)) return Outcome::kDuplicate;
  backend_.addKeyframe(id, stamp, T_odom_base, information);
  clouds_.add(id, cloud, backend_);
  newest_keyframe_ = std::max(newest_keyframe_, id);
  if (options_.keep_journal) {
    const nlohmann::json entry = {{"id", id},
                                  {"stamp", stamp},
                                  {"odom_pose", poseToJson(T_odom_base)},
                                  {"information", matrixToJson(information)}};
    journal_keyframes_.push_back(entry.dump());
  }
  flushPending(id);
  dropStalePending();
  return Outcome::kAdded;
}

BackendSession::Outcome BackendSession::addWalls(uint32_t keyframe_id, const KeyframeWalls& walls) {
  if (!backend_.hasKeyframe(keyframe_id)) {
    if (keyframeCount() > 0 && keyframe_id + options_.max_pending_keyframes < newest_keyframe_) {
      return Outcome::kDropped;  // its keyframe is long gone (lost message or another run)
    }
    KeyframeWalls& pending = pending_walls_[keyframe_id];
    pending.walls.insert(pending.walls.end(), walls.walls.begin(), walls.walls.end());
    pending.seen_over.insert(pending.seen_over.end(), walls.seen_over.begin(),
                             walls.seen_over.end());
    return Outcome::kBuffered;
  }
  if (!walls_taken_.insert(keyframe_id).second) return Outcome::kDuplicate;
  if (walls.walls.empty() && walls.seen_over.empty()) return Outcome::kAdded;
  backend_.addWallObservations(keyframe_id, walls.walls, walls.seen_over);
  if (!options_.keep_journal) return Outcome::kAdded;
  nlohmann::json entry = {{"keyframe", keyframe_id}, {"walls", nlohmann::json::array()}};
  for (const WallSegment& w : walls.walls) entry["walls"].push_back(wallToJson(w));
  if (!walls.seen_over.empty()) {
    entry["seen_over"] = nlohmann::json::array();
    for (const WallSegment& w : walls.seen_over) entry["seen_over"].push_back(wallToJson(w));
  }
  journal_walls_.push_back(entry.dump());
  return Outcome::kAdded;
}

BackendSession::Outcome BackendSession::addLoop(const LoopEdge& edge, const Matrix6d& information) {
  if (!backend_.hasKeyframe(edge.from) || !backend_.hasKeyframe(edge.to)) {
    pending_loops_.emplace_back(edge, information);
    return Outcome::kBuffered;
  }
  if (!loops_taken_.emplace(edge.from, edge.to).second) return Outcome::kDuplicate;
  backend_.addLoopClosure(edge.from, edge.to, edge.relativePose(), information, edge.score);
  if (!options_.keep_journal) return Outcome::kAdded;
  const nlohmann::json entry = {{"from", edge.from},
                                {"to", edge.to},
                                {"relative_pose", poseToJson(edge.relativePose())},
                                {"information", matrixToJson(information)},
                                {"score", edge.score}};
  journal_loops_.push_back(entry.dump());
  return Outcome::kAdded;
}

BackendSession::Outcome BackendSession::addLoop(const LoopClosure& loop) {
  LoopEdge edge;
  edge.from = loop.from;
  edge.to = loop.to;
  edge.position = loop.T_from_to.translation();
  edge.orientation = Eigen::Quaterniond(loop.T_from_to.rotation()).normalized();
  edge.score = loop.score;
  return addLoop(edge, loop.information);
}

void BackendSession::flushPending(uint32_t keyframe_id) {
  const auto walls = pending_walls_.find(keyframe_id);
  if (walls != pending_walls_.end()) {
    const KeyframeWalls segments = std::move(walls->second);
    pending_walls_.erase(walls);
    addWalls(keyframe_id, segments);
  }
  std::vector<std::pair<LoopEdge, Matrix6d>> loops;
  loops.swap(pending_loops_);
  for (const auto& [edge, information] : loops) addLoop(edge, information);
}

void BackendSession::dropStalePending() {
  while (!pending_walls_.empty() &&
         pending_walls_.begin()->first + options_.max_pending_keyframes < newest_keyframe_) {
    pending_walls_.erase(pending_walls_.begin());
  }
  if (pending_loops_.size() > options_.max_pending_keyframes) {
    pending_loops_.erase(pending_loops_.begin());
  }
}

size_t BackendSession::pendingCount() const {
  return pending_walls_.size() + pending_loops_.size();
}

void BackendSession::removeRoom(uint32_t id) {
  backend_.removeRoom(id);
  journal_rooms_.erase(id);
  wall_to_wall_.erase(id);
}

bool BackendSession::takeRoom(const MappedRoom& room, const std::vector<uint32_t>& absorbed,
                              const std::vector<std::pair<uint32_t, uint32_t>>& wall_to_wall) {
  for (uint32_t id : absorbed) removeRoom(id);
  return setRoom(room, wall_to_wall);
}

size_t BackendSession::retainRooms(const std::set<uint32_t>& ids) {
  std::vector<uint32_t> gone;
  for (const auto& [id, room] : journal_rooms_) {
    if (ids.count(id) == 0) gone.push_back(id);
  }
  for (uint32_t id : gone) removeRoom(id);
  return gone.size();
}

uint32_t BackendSession::firstIncompleteKeyframe() const {
  if (keyframeCount() == 0) return 0;
  // Walls older than the pending window would be dropped anyway.
  const uint32_t window = static_cast<uint32_t>(options_.max_pending_keyframes);
  const uint32_t oldest = newest_keyframe_ > window ? newest_keyframe_ - window : 0;
  for (uint32_t id = oldest; id <= newest_keyframe_; ++id) {
    if (backend_.hasKeyframe(id) && walls_taken_.count(id) == 0) return id;
  }
  return newest_keyframe_ + 1;
}

std::vector<uint32_t> BackendSession::missingKeyframes() const {
  std::vector<uint32_t> missing;
  for (uint32_t id = 0; id < newest_keyframe_; ++id) {
    if (!backend_.hasKeyframe(id)) missing.push_back(id);
  }
  return missing;
}

bool BackendSession::setRoom(const MappedRoom& room,
                             const std::vector<std::pair<uint32_t, uint32_t>>& wall_to_wall) {
  if (!backend_.setRoom(room)) return false;
  std::set<std::pair<uint32_t, uint32_t>>& pairs = wall_to_wall_[room.id];
  for (const auto& pair : wall_to_wall) {
    // An edge sent again (rooms republished after a restart) is one factor, not two.
    if (pairs.insert(pair).second) backend_.addWallToWall(pair.first, pair.second);
  }
  nlohmann::json entry = roomToJson(room);
  entry["wall_to_wall"] = nlohmann::json::array();
  for (const auto& [mapped, observed] : pairs) entry["wall_to_wall"].push_back({mapped, observed});
  journal_rooms_[room.id] = std::move(entry);
  return true;
}

std::map<uint32_t, uint32_t> BackendSession::wallObservationCounts() const {
  std::map<uint32_t, uint32_t> counts;
  for (const auto& [id, lm] : backend_.wallMap().landmarks()) counts[id] = lm.observations;
  return counts;
}

PointCloud BackendSession::mapCloud(double voxel_m) const {
  PointCloud cloud = buildMapCloud(sceneGraph(), clouds_.clouds(), voxel_m);
  if (recovered_map_) cloud += *recovered_map_;
  return cloud;
}

nlohmann::json BackendSession::journal() const { return nlohmann::json::parse(journalText()); }

std::string BackendSession::journalText() const {
  const auto array = [](const std::vector<std::string>& entries) {
    std::string out = "[";
    for (size_t i = 0; i < entries.size(); ++i) {
      if (i > 0) out += ',';
      out += entries[i];
    }
    return out + "]";
  };
  nlohmann::json rooms = nlohmann::json::array();
  for (const auto& [id, room] : journal_rooms_) rooms.push_back(room);
  return "{\"format\":\"tacs_graphs/backend_journal\",\"version\":1,\"keyframes\":" +
         array(journal_keyframes_) + ",\"walls\":" + array(journal_walls_) +
         ",\"loops\":" + array(journal_loops_) + ",\"rooms\":" + rooms.dump() + "}";
}

SceneGraph BackendSession::sceneGraph() const {
  SceneGraph graph = backend_.sceneGraph();
  if (freeStandingFurnitureBoundsNoRoom(config_.rooms)) {
    const auto bounding = roomBoundingPlanes(backend_.wallMap(), config_.rooms.extraction);
    for (auto& [id, wall] : graph.walls) wall.is_wall = wall.is_wall && bounding.count(id) > 0;
  }
  graph.input = scan_input_;
  return graph;
}

void BackendSession::noteScanInput(const ScanInput& input) {
  ScanInput& kept = scan_input_ ? *scan_input_ : scan_input_.emplace();
  kept.scans_received = std::max(kept.scans_received, input.scans_received);
  kept.scans_missing = std::max(kept.scans_missing, input.scans_missing);
}

nlohmann::json BackendSession::runStatus(const std::string& status) const {
  nlohmann::json j = {
      {"format", "tacs_graphs/backend_run"},
      {"status", status},
      {"keyframes", keyframeCount()},
      {"missing_keyframes", missingKeyframes()},
      {"rooms", roomCount()},
      {"files",
       {"scene_graph.json", "trajectory_tum.txt", "backend_journal.json", "map.pcd", "map.bt"}}};
  if (scan_input_) {
    j["scans_received"] = scan_input_->scans_received;
    j["scans_missing"] = scan_input_->scans_missing;
  }
  return j;
}

void BackendSession::save(const std::string& dir, const MapExportConfig& map_config) const {
  ensureDirectory(dir);
  // run.json says "saving" until the last product is in: a save cut short (a SIGKILL) never
  // leaves a set that looks complete, nor an older run's map.bt beside the new graph.
  writeFileAtomically(dir + "/run.json", runStatus("saving").dump(2) + "\n");
  std::remove((dir + "/map.bt").c_str());
  const SceneGraph graph = sceneGraph();
  // Fastest first: a shutdown cut short (roslaunch escalates to SIGTERM after its SIGINT
  // timeout) still leaves the graph, the journal and the cloud; the OctoMap ray casting comes last.
  graph.save(dir + "/scene_graph.json");
  Trajectory keyframes;
  for (const auto& [id, kf] : graph.keyframes) keyframes.push_back({kf.stamp, kf.pose()});
  std::sort(keyframes.begin(), keyframes.end(),
            [](const StampedPose& a, const StampedPose& b) { return a.stamp < b.stamp; });
  writeTum(dir + "/trajectory_tum.txt", keyframes);
  writeFileAtomically(dir + "/backend_journal.json", journalText());
  writePcdAtomically(dir + "/map.pcd", mapCloud(map_config.cloud_voxel_m));
  writeOctomap(dir + "/map.bt", graph, clouds_.clouds(), map_config, sensor_in_base_);
  writeFileAtomically(dir + "/run.json", runStatus("complete").dump(2) + "\n");
}

size_t BackendSession::recover(const std::string& dir) {
  const std::string path = dir + "/backend_journal.json";
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    std::map<uint32_t, KeyframeWalls> walls;
    for (const auto& w : j.at("walls")) {
      KeyframeWalls& kf = walls[w.at("keyframe").get<uint32_t>()];
      for (const auto& s : w.at("walls")) kf.walls.push_back(wallFromJson(s));
      // Journals written before surfaces seen over were reported have none.
      if (w.contains("seen_over")) {
        for (const auto& s : w.at("seen_over")) kf.seen_over.push_back(wallFromJson(s));
      }
    }
    size_t recovered = 0;
    for (const auto& k : j.at("keyframes")) {
      const uint32_t id = k.at("id").get<uint32_t>();
      if (addKeyframe(id, k.at("stamp").get<double>(), poseFromJson(k.at("odom_pose")),
                      matrixFromJson(k.at("information")), nullptr) == Outcome::kAdded) {
        ++recovered;
      }
      const auto it = walls.find(id);
      if (it != walls.end()) addWalls(id, it->second);
    }
    for (const auto& l : j.at("loops")) {
      LoopEdge edge;
      edge.from = l.at("from").get<uint32_t>();
      edge.to = l.at("to").get<uint32_t>();
      const Pose3 T = poseFromJson(l.at("relative_pose"));
      edge.position = T.translation();
      edge.orientation = Eigen::Quaterniond(T.rotation());
      edge.score = l.at("score").get<double>();
      addLoop(edge, matrixFromJson(l.at("information")));
    }
    // Rooms last: their factors need the walls.
    for (const auto& r : j.at("rooms")) {
      std::vector<std::pair<uint32_t, uint32_t>> pairs;
      for (const auto& p : r.at("wall_to_wall")) {
        pairs.emplace_back(p.at(0).get<uint32_t>(), p.at(1).get<uint32_t>());
      }
      setRoom(roomFromJson(r), pairs);
    }
    if (recovered > 0) backend_.optimize();
    PointCloud::Ptr map(new PointCloud);
    if (pcl::io::loadPCDFile(dir + "/map.pcd", *map) == 0) recovered_map_ = map;
    return recovered;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

}  // namespace tacs
