#include "tacs_graphs/scene_graph/scene_graph.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "tacs_graphs/common/file_io.h"

namespace tacs {
namespace {

using nlohmann::json;

constexpr const char* kFormat = "tacs_graphs/scene_graph";
constexpr int kVersion = 1;

json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
json vec(const Eigen::Vector2d& v) { return {v.x(), v.y()}; }
json quat(const Eigen::Quaterniond& q) { return {q.x(), q.y(), q.z(), q.w()}; }

// Field readers that name the JSON path of what is wrong.
const json& field(const json& j, const char* key, const std::string& path) {
  if (!j.is_object() || !j.contains(key)) {
    throw std::runtime_error((path.empty() ? "" : path + ".") + key + ": missing");
  }
  return j.at(key);
}

double number(const json& j, const std::string& path) {
  if (!j.is_number()) throw std::runtime_error(path + ": expected a number, got " + j.dump());
  return j.get<double>();
}

uint32_t index(const json& j, const std::string& path) {
  if (!j.is_number_unsigned() && !(j.is_number_integer() && j.get<int64_t>() >= 0)) {
    throw std::runtime_error(path + ": expected a non-negative integer, got " + j.dump());
  }
  return j.get<uint32_t>();
}

template <int N>
Eigen::Matrix<double, N, 1> vector(const json& j, const std::string& path) {
  if (!j.is_array() || j.size() != N) {
    throw std::runtime_error(path + ": expected " + std::to_string(N) + " numbers, got " +
                             j.dump());
  }
  Eigen::Matrix<double, N, 1> v;
  for (int i = 0; i < N; ++i) v[i] = number(j[i], path + "[" + std::to_string(i) + "]");
  return v;
}

Eigen::Quaterniond quaternion(const json& j, const std::string& path) {
  const Eigen::Vector4d v = vector<4>(j, path);
  if (std::abs(v.norm() - 1.0) > 1e-3) throw std::runtime_error(path + ": not a unit quaternion");
  return Eigen::Quaterniond(v[3], v[0], v[1], v[2]);
}

const json& array(const json& j, const char* key, const std::string& path) {
  const json& a = field(j, key, path);
  if (!a.is_array()) {
    throw std::runtime_error((path.empty() ? "" : path + ".") + key + ": expected a list");
  }
  return a;
}

std::vector<uint32_t> indices(const json& j, const std::string& path) {
  if (!j.is_array()) throw std::runtime_error(path + ": expected a list");
  std::vector<uint32_t> out;
  for (size_t i = 0; i < j.size(); ++i)
    out.push_back(index(j[i], path + "[" + std::to_string(i) + "]"));
  return out;
}

}  // namespace

Pose3 KeyframeNode::pose() const {
  Pose3 p = Pose3::Identity();
  p.linear() = orientation.normalized().toRotationMatrix();
  p.translation() = position;
  return p;
}

void KeyframeNode::setPose(const Pose3& T_map_base) {
  position = T_map_base.translation();
  orientation = Eigen::Quaterniond(T_map_base.rotation()).normalized();
}

Pose3 LoopEdge::relativePose() const {
  Pose3 p = Pose3::Identity();
  p.linear() = orientation.normalized().toRotationMatrix();
  p.translation() = position;
  return p;
}

const char* roomKindName(RoomKind kind) { return kind == RoomKind::kRoom ? "room" : "corridor"; }

size_t SceneGraph::wallCount() const {
  return static_cast<size_t>(
      std::count_if(walls.begin(), walls.end(), [](const auto& w) { return w.second.is_wall; }));
}

SceneGraph SceneGraph::transformed(const Pose3& T) const {
  SceneGraph out = *this;
  const Eigen::Rotation2Dd yaw(std::atan2(T.linear()(1, 0), T.linear()(0, 0)));
  const Eigen::Vector2d shift = T.translation().head<2>();
  const auto move2 = [&](const Eigen::Vector2d& p) -> Eigen::Vector2d { return yaw * p + shift; };
  for (auto& [id, kf] : out.keyframes) kf.setPose(T * kf.pose());
  for (auto& [id, w] : out.walls) {
    // n . p + d = 0 in the old frame; a point p' = T p gives (R n) . p' + d - (R n) . t = 0.
    w.normal = T.linear() * w.normal;
    w.d -= w.normal.dot(T.translation());
    for (auto& e : w.endpoints) e = move2(e);
    for (double& z : w.z_range) z += T.translation().z();
  }
  for (auto& [id, r] : out.rooms) {
    r.center = T * r.center;
    for (auto& p : r.free_space) p = move2(p);
  }
  return out;
}

json SceneGraph::toJson() const {
  json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["keyframes"] = json::array();
  for (const auto& [id, kf] : keyframes) {
    j["keyframes"].push_back({{"id", id},
                              {"stamp", kf.stamp},
                              {"position", vec(kf.position)},
                              {"orientation", quat(kf.orientation)},
                              {"room_id", kf.room_id}});
  }
  j["walls"] = json::array();
  for (const auto& [id, w] : walls) {
    j["walls"].push_back({{"id", id},
                          {"normal", vec(w.normal)},
                          {"d", w.d},
                          {"endpoints", {vec(w.endpoints[0]), vec(w.endpoints[1])}},
                          {"z_range", {w.z_range[0], w.z_range[1]}},
                          {"is_wall", w.is_wall}});
  }
  j["rooms"] = json::array();
  for (const auto& [id, r] : rooms) {
    json free_space = json::array();
    for (const auto& p : r.free_space) free_space.push_back(vec(p));
    j["rooms"].push_back({{"id", id},
                          {"kind", roomKindName(r.kind)},
                          {"center", vec(r.center)},
                          {"wall_ids", r.wall_ids},
                          {"free_space", free_space},
                          {"keyframe_ids", r.keyframe_ids}});
  }
  j["loops"] = json::array();
  for (const auto& l : loops) {
    j["loops"].push_back(
        {{"from", l.from},
         {"to", l.to},
         {"relative_pose", {{"position", vec(l.position)}, {"orientation", quat(l.orientation)}}},
         {"score", l.score}});
  }
  if (input) {
    j["input"] = {{"scans_received", input->scans_received},
                  {"scans_missing", input->scans_missing},
                  {"drop_ratio", input->dropRatio()}};
  }
  return j;
}

namespace {

// One parser per node kind of fromJson(); `p` names the element in errors ("walls[3]").
KeyframeNode keyframeFromJson(const json& k, const std::string& p) {
  KeyframeNode kf;
  kf.id = index(field(k, "id", p), p + ".id");
  kf.stamp = number(field(k, "stamp", p), p + ".stamp");
  kf.position = vector<3>(field(k, "position", p), p + ".position");
  kf.orientation = quaternion(field(k, "orientation", p), p + ".orientation");
  const json& room = field(k, "room_id", p);
  if (!room.is_number_integer()) throw std::runtime_error(p + ".room_id: expected an integer");
  kf.room_id = room.get<int>();
  return kf;
}

WallNode wallFromJson(const json& wall, const std::string& p) {
  WallNode w;
  w.id = index(field(wall, "id", p), p + ".id");
  w.normal = vector<3>(field(wall, "normal", p), p + ".normal");
  w.d = number(field(wall, "d", p), p + ".d");
  const json& ends = field(wall, "endpoints", p);
  if (!ends.is_array() || ends.size() != 2) {
    throw std::runtime_error(p + ".endpoints: expected [[x, y], [x, y]]");
  }
  w.endpoints[0] = vector<2>(ends[0], p + ".endpoints[0]");
  w.endpoints[1] = vector<2>(ends[1], p + ".endpoints[1]");
  const Eigen::Vector2d z = vector<2>(field(wall, "z_range", p), p + ".z_range");
  w.z_range = {z[0], z[1]};
  // Optional: graphs saved before surfaces were told apart hold walls only.
  if (wall.contains("is_wall")) {
    if (!wall["is_wall"].is_boolean()) throw std::runtime_error(p + ".is_wall: expected a boolean");
    w.is_wall = wall["is_wall"].get<bool>();
  }
  return w;
}

RoomNode roomFromJson(const json& room, const std::string& p) {
  RoomNode r;
  r.id = index(field(room, "id", p), p + ".id");
  const json& kind = field(room, "kind", p);
  if (kind == "room") {
    r.kind = RoomKind::kRoom;
  } else if (kind == "corridor") {
    r.kind = RoomKind::kCorridor;
  } else {
    throw std::runtime_error(p + ".kind: expected \"room\" or \"corridor\", got " + kind.dump());
  }
  r.center = vector<3>(field(room, "center", p), p + ".center");
  r.wall_ids = indices(field(room, "wall_ids", p), p + ".wall_ids");
  const json& fs = array(room, "free_space", p);
  for (size_t k = 0; k < fs.size(); ++k) {
    r.free_space.push_back(vector<2>(fs[k], p + ".free_space[" + std::to_string(k) + "]"));
  }
  r.keyframe_ids = indices(field(room, "keyframe_ids", p), p + ".keyframe_ids");
  return r;
}

LoopEdge loopFromJson(const json& loop, const std::string& p) {
  LoopEdge l;
  l.from = index(field(loop, "from", p), p + ".from");
  l.to = index(field(loop, "to", p), p + ".to");
  const json& rel = field(loop, "relative_pose", p);
  l.position =
      vector<3>(field(rel, "position", p + ".relative_pose"), p + ".relative_pose.position");
  l.orientation =
      quaternion(field(rel, "orientation", p + ".relative_pose"), p + ".relative_pose.orientation");
  l.score = number(field(loop, "score", p), p + ".score");
  return l;
}

// Calls parse(element, "<key>[i]") for each element of the array j[key].
template <class Parse>
void forEachIn(const json& j, const std::string& key, const Parse& parse) {
  const json& elements = array(j, key.c_str(), "");
  for (size_t i = 0; i < elements.size(); ++i) {
    parse(elements[i], key + "[" + std::to_string(i) + "]");
  }
}

}  // namespace

SceneGraph SceneGraph::fromJson(const json& j) {
  if (!j.is_object() || j.value("format", "") != kFormat) {
    throw std::runtime_error(std::string("format: expected \"") + kFormat + "\"");
  }
  if (j.value("version", 0) != kVersion) {
    throw std::runtime_error("version: expected " + std::to_string(kVersion));
  }
  SceneGraph g;
  forEachIn(j, "keyframes", [&](const json& e, const std::string& p) {
    const KeyframeNode kf = keyframeFromJson(e, p);
    g.keyframes[kf.id] = kf;
  });
  forEachIn(j, "walls", [&](const json& e, const std::string& p) {
    const WallNode w = wallFromJson(e, p);
    g.walls[w.id] = w;
  });
  forEachIn(j, "rooms", [&](const json& e, const std::string& p) {
    const RoomNode r = roomFromJson(e, p);
    g.rooms[r.id] = r;
  });
  forEachIn(j, "loops",
            [&](const json& e, const std::string& p) { g.loops.push_back(loopFromJson(e, p)); });
  if (j.contains("input")) {
    const json& in = j.at("input");
    ScanInput s;
    s.scans_received = index(field(in, "scans_received", "input"), "input.scans_received");
    s.scans_missing = index(field(in, "scans_missing", "input"), "input.scans_missing");
    g.input = s;
  }
  return g;
}

void SceneGraph::save(const std::string& path) const {
  writeFileAtomically(path, toJson().dump(1) + "\n");
}

SceneGraph SceneGraph::load(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open file");
  json j;
  try {
    j = json::parse(in);
  } catch (const json::parse_error& e) {
    throw std::runtime_error(path + ": not valid JSON: " + e.what());
  }
  try {
    return fromJson(j);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

}  // namespace tacs
