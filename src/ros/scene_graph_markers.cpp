#include "tacs_graphs/ros/scene_graph_markers.h"

#include <cmath>

#include "tacs_graphs/ros/message_conversion.h"
#include "tacs_graphs/scene_graph/room_floor.h"
#include "tacs_graphs/viz/scene_graph_drawing.h"

namespace tacs {
namespace {

using visualization_msgs::Marker;

std_msgs::ColorRGBA rgba(float r, float g, float b, float a = 1.0f) {
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

geometry_msgs::Point point(double x, double y, double z) {
  geometry_msgs::Point p;
  p.x = x;
  p.y = y;
  p.z = z;
  return p;
}

geometry_msgs::Point point(const Eigen::Vector3d& v) { return point(v.x(), v.y(), v.z()); }

Marker makeMarker(const std::string& frame, double stamp, const std::string& ns, int id, int type) {
  Marker m;
  m.header.frame_id = frame;
  m.header.stamp.fromSec(stamp);
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.action = Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.scale.x = m.scale.y = m.scale.z = 1.0;
  return m;
}

// Midpoint of a wall's extent at mid height: where room-to-wall lines end.
Eigen::Vector3d wallAnchor(const WallNode& w) {
  const Eigen::Vector2d mid = 0.5 * (w.endpoints[0] + w.endpoints[1]);
  return {mid.x(), mid.y(), 0.5 * (w.z_range[0] + w.z_range[1])};
}

void addWalls(const SceneGraph& graph, const std::string& frame, double stamp,
              visualization_msgs::MarkerArray* out) {
  for (const auto& [id, w] : graph.walls) {
    Marker m = makeMarker(frame, stamp, w.is_wall ? "walls" : "other_planes", static_cast<int>(id),
                          Marker::CUBE);
    const Eigen::Vector2d axis = w.endpoints[1] - w.endpoints[0];
    const double length = std::max(axis.norm(), 0.05);
    const double height = std::max(w.z_range[1] - w.z_range[0], 0.05);
    // The box lies along the extent; its yaw follows the wall direction (or the normal when the
    // extent is degenerate).
    const double yaw = axis.norm() > 1e-6 ? std::atan2(axis.y(), axis.x())
                                          : std::atan2(w.normal.x(), -w.normal.y());
    m.pose = toPoseMsg(poseFromXyzRpy(0, 0, 0, 0, 0, yaw));
    m.pose.position = point(wallAnchor(w));
    m.scale.x = length;
    m.scale.y = 0.08;
    m.scale.z = height;
    // Colour by facing direction so the two faces of a wall and the axes stand apart; other
    // planes grey and faint.
    const double hue = std::atan2(w.normal.y(), w.normal.x());
    m.color = w.is_wall ? rgba(0.5f + 0.5f * std::cos(hue), 0.5f + 0.5f * std::sin(hue),
                               0.5f - 0.5f * std::cos(hue), 0.85f)
                        : rgba(0.6f, 0.6f, 0.6f, 0.4f);
    out->markers.push_back(m);
  }
}

void addRooms(const SceneGraph& graph, const std::string& frame, double stamp,
              visualization_msgs::MarkerArray* out) {
  // Rooms float above the walls, as in the layered drawing of the paper's Fig. 1.
  const double room_z = 3.5;
  Marker lines = makeMarker(frame, stamp, "room_walls", 0, Marker::LINE_LIST);
  lines.scale.x = 0.03;
  lines.color = rgba(0.9f, 0.6f, 0.1f, 0.8f);
  for (const auto& [id, r] : graph.rooms) {
    Marker m = makeMarker(frame, stamp, "rooms", static_cast<int>(id), Marker::CUBE);
    m.pose.position = point(r.center.x(), r.center.y(), room_z);
    m.scale.x = m.scale.y = 0.5;
    m.scale.z = 0.05;
    m.color = r.kind == RoomKind::kCorridor ? rgba(0.1f, 0.4f, 1.0f) : rgba(1.0f, 0.5f, 0.0f);
    out->markers.push_back(m);
    for (const uint32_t wid : r.wall_ids) {
      const auto it = graph.walls.find(wid);
      if (it == graph.walls.end()) continue;
      lines.points.push_back(m.pose.position);
      lines.points.push_back(point(wallAnchor(it->second)));
    }
  }
  if (!lines.points.empty()) out->markers.push_back(lines);
}

// Each room's floor (scene_graph/room_floor.h) as a layer of flat cells just above the ground,
// coloured as the room in topdown.png.
void addRoomFloors(const SceneGraph& graph, const std::string& frame, double stamp,
                   visualization_msgs::MarkerArray* out) {
  RoomFloorConfig config;
  config.cell_m = 0.2;  // coarser than the evaluation's grid: a light message
  for (const auto& [id, cells] : roomFloors(graph, config)) {
    if (cells.empty()) continue;
    Marker m = makeMarker(frame, stamp, "room_floors", static_cast<int>(id), Marker::CUBE_LIST);
    m.scale.x = m.scale.y = config.cell_m;
    m.scale.z = 0.02;
    const viz::Rgba c = viz::roomColor(id, 255);
    m.color = rgba(c.r / 255.0f, c.g / 255.0f, c.b / 255.0f, 0.35f);
    for (const auto& cell : cells) {
      m.points.push_back(
          point((cell.x() + 0.5) * config.cell_m, (cell.y() + 0.5) * config.cell_m, 0.02));
    }
    out->markers.push_back(m);
  }
}

}  // namespace

visualization_msgs::MarkerArray sceneGraphMarkers(const SceneGraph& graph, const std::string& frame,
                                                  double stamp) {
  visualization_msgs::MarkerArray out;
  Marker clear;
  clear.header.frame_id = frame;
  clear.action = Marker::DELETEALL;
  out.markers.push_back(clear);

  Marker keyframes = makeMarker(frame, stamp, "keyframes", 0, Marker::SPHERE_LIST);
  keyframes.scale.x = keyframes.scale.y = keyframes.scale.z = 0.12;
  keyframes.color = rgba(1.0f, 0.1f, 0.1f);
  Marker trajectory = makeMarker(frame, stamp, "trajectory", 0, Marker::LINE_STRIP);
  trajectory.scale.x = 0.04;
  trajectory.color = rgba(1.0f, 1.0f, 0.2f);
  for (const auto& [id, kf] : graph.keyframes) {
    keyframes.points.push_back(point(kf.position));
    trajectory.points.push_back(point(kf.position));
  }
  if (!keyframes.points.empty()) out.markers.push_back(keyframes);
  if (trajectory.points.size() >= 2) out.markers.push_back(trajectory);

  addWalls(graph, frame, stamp, &out);
  addRooms(graph, frame, stamp, &out);
  addRoomFloors(graph, frame, stamp, &out);

  Marker loops = makeMarker(frame, stamp, "loops", 0, Marker::LINE_LIST);
  loops.scale.x = 0.06;
  loops.color = rgba(1.0f, 0.0f, 1.0f);
  for (const LoopEdge& l : graph.loops) {
    const auto a = graph.keyframes.find(l.from);
    const auto b = graph.keyframes.find(l.to);
    if (a == graph.keyframes.end() || b == graph.keyframes.end()) continue;
    loops.points.push_back(point(a->second.position));
    loops.points.push_back(point(b->second.position));
  }
  if (!loops.points.empty()) out.markers.push_back(loops);
  return out;
}

visualization_msgs::MarkerArray priorMapMarkers(const SceneGraph& prior,
                                                const std::map<uint32_t, uint32_t>& room_pairs,
                                                const std::string& frame, double stamp) {
  visualization_msgs::MarkerArray out = sceneGraphMarkers(prior, frame, stamp);
  int id = 0;
  for (const auto& [session_room, prior_room] : room_pairs) {
    const auto it = prior.rooms.find(prior_room);
    if (it == prior.rooms.end()) continue;
    const Eigen::Vector3d& c = it->second.center;
    Marker pillar = makeMarker(frame, stamp, "matched_rooms", id++, Marker::CYLINDER);
    pillar.pose.position = point(c.x(), c.y(), 1.75);
    pillar.scale.x = pillar.scale.y = 0.4;
    pillar.scale.z = 3.5;
    pillar.color = rgba(0.1f, 0.9f, 0.2f, 0.7f);
    out.markers.push_back(pillar);
    Marker label = makeMarker(frame, stamp, "matched_rooms", id++, Marker::TEXT_VIEW_FACING);
    label.pose.position = point(c.x(), c.y(), 4.0);
    label.scale.z = 0.5;
    label.color = rgba(0.1f, 0.9f, 0.2f);
    label.text = "prior " + std::to_string(prior_room) + " = room " + std::to_string(session_room);
    out.markers.push_back(label);
  }
  return out;
}

visualization_msgs::Marker traversableGraphMarker(const TravGraph& graph_in_base,
                                                  const Pose3& T_frame_base, uint32_t keyframe_id,
                                                  const std::string& frame, double stamp) {
  Marker m = makeMarker(frame, stamp, "traversable_graph", static_cast<int>(keyframe_id),
                        Marker::LINE_LIST);
  m.scale.x = 0.015;
  for (const auto& [a, b] : graph_in_base.edges) {
    const TravNode& na = graph_in_base.nodes[a];
    const TravNode& nb = graph_in_base.nodes[b];
    const bool safe = na.safe && nb.safe;
    const std_msgs::ColorRGBA c =
        safe ? rgba(0.0f, 0.6f, 0.2f, 0.7f) : rgba(0.5f, 1.0f, 0.5f, 0.5f);
    m.points.push_back(point(T_frame_base * na.position));
    m.points.push_back(point(T_frame_base * nb.position));
    m.colors.push_back(c);
    m.colors.push_back(c);
  }
  return m;
}

}  // namespace tacs
