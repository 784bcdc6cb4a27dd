#include "tacs_graphs/ros/graph_messages.h"

#include "tacs_graphs/ros/cloud_conversion.h"
#include "tacs_graphs/ros/message_conversion.h"

namespace tacs {
namespace {

geometry_msgs::Point toPoint2(const Eigen::Vector2d& p) { return toPoint({p.x(), p.y(), 0.0}); }

}  // namespace

tacs_graphs::Keyframe toKeyframeMsg(uint32_t id, double stamp, const Pose3& T_odom_base,
                                    const Matrix6d& information, const PointCloud& cloud,
                                    const Eigen::Vector3d& sensor_in_base,
                                    const std::string& odom_frame, const std::string& base_frame) {
  tacs_graphs::Keyframe msg;
  msg.header.stamp.fromSec(stamp);
  msg.header.frame_id = odom_frame;
  msg.id = id;
  msg.odom_pose = toPoseMsg(T_odom_base);
  toMatrixArray(information, &msg.odom_information);
  msg.cloud = toRosCloud(cloud, base_frame, stamp);
  msg.sensor_origin = toPoint(sensor_in_base);
  return msg;
}

tacs_graphs::WallObservation toWallObservationMsg(const WallSegment& wall) {
  tacs_graphs::WallObservation msg;
  msg.normal = toVector(wall.normal);
  msg.d = wall.d;
  msg.inlier_count = wall.inliers;
  msg.endpoints[0] = toPoint2(wall.endpoints[0]);
  msg.endpoints[1] = toPoint2(wall.endpoints[1]);
  msg.z_min = wall.z_min;
  msg.z_max = wall.z_max;
  return msg;
}

WallSegment fromWallObservationMsg(const tacs_graphs::WallObservation& msg) {
  WallSegment wall;
  wall.normal = fromVector(msg.normal);
  wall.d = msg.d;
  wall.inliers = msg.inlier_count;
  for (int i = 0; i < 2; ++i) wall.endpoints[i] = {msg.endpoints[i].x, msg.endpoints[i].y};
  wall.z_min = msg.z_min;
  wall.z_max = msg.z_max;
  return wall;
}

tacs_graphs::TraversableGraph toTraversableGraphMsg(const TravGraph& graph, uint32_t keyframe_id,
                                                    const Pose3& T_odom_base,
                                                    const std::string& base_frame, double stamp,
                                                    const Pose3& T_base_ground) {
  tacs_graphs::TraversableGraph msg;
  msg.header.stamp.fromSec(stamp);
  msg.header.frame_id = base_frame;
  msg.keyframe_id = keyframe_id;
  // The message field is unsigned: a graph without a root points past the node list.
  msg.root_index = graph.root >= 0 ? static_cast<uint32_t>(graph.root) : graph.nodes.size();
  msg.odom_pose = toPoseMsg(T_odom_base);
  msg.ground_in_base = toPoseMsg(T_base_ground);
  msg.nodes.reserve(graph.nodes.size());
  for (const TravNode& n : graph.nodes) {
    tacs_graphs::TraversableNode m;
    m.position = toPoint(n.position);
    m.normal = toVector(n.normal);
    m.label = static_cast<uint8_t>(n.label);
    m.inferred = n.inferred;
    m.traversable = n.traversable;
    m.safe = n.safe;
    m.variance = n.variance;
    m.clearance = n.clearance;
    msg.nodes.push_back(m);
  }
  msg.edges.reserve(graph.edges.size());
  for (const auto& [a, b] : graph.edges) {
    tacs_graphs::TraversableEdge e;
    e.source = a;
    e.target = b;
    msg.edges.push_back(e);
  }
  return msg;
}

TravGraph fromTraversableGraphMsg(const tacs_graphs::TraversableGraph& msg) {
  TravGraph graph;
  graph.root = msg.root_index < msg.nodes.size() ? static_cast<int>(msg.root_index) : -1;
  for (const auto& m : msg.nodes) {
    TravNode n;
    n.position = fromPoint(m.position);
    n.normal = fromVector(m.normal);
    n.label = m.label <= 2 ? static_cast<TravLabel>(m.label) : TravLabel::kUnknown;
    n.inferred = m.inferred;
    n.traversable = m.traversable;
    n.safe = m.safe;
    n.variance = m.variance;
    n.clearance = m.clearance;
    graph.nodes.push_back(n);
  }
  for (const auto& e : msg.edges) {
    if (e.source < msg.nodes.size() && e.target < msg.nodes.size()) {
      graph.edges.emplace_back(e.source, e.target);
    }
  }
  return graph;
}

tacs_graphs::RoomObservation toRoomObservationMsg(const MappedRoom& room,
                                                  const RoomAssociation& association) {
  tacs_graphs::RoomObservation msg;
  const RoomObservation& r = room.room;
  msg.room_id = room.id;
  msg.kind = r.kind == RoomKind::kCorridor ? tacs_graphs::RoomObservation::CORRIDOR
                                           : tacs_graphs::RoomObservation::ROOM;
  for (size_t i = 0; i < r.walls.size(); ++i) msg.wall_ids[i] = r.walls[i];
  msg.center = toPoint(r.center);
  msg.axes_yaw = r.axes_yaw;
  msg.free_space.reserve(r.free_space.size());
  for (const auto& p : r.free_space) msg.free_space.push_back(toPoint(p));
  msg.keyframe_ids.assign(r.keyframe_ids.begin(), r.keyframe_ids.end());
  msg.redetected = !association.created;
  for (const auto& [mapped, observed] : association.wall_to_wall) {
    msg.wall_to_wall.push_back(mapped);
    msg.wall_to_wall.push_back(observed);
  }
  msg.absorbed_room_ids.assign(association.absorbed.begin(), association.absorbed.end());
  return msg;
}

MappedRoom fromRoomObservationMsg(const tacs_graphs::RoomObservation& msg) {
  MappedRoom room;
  room.id = msg.room_id;
  room.observations = 1;
  RoomObservation& r = room.room;
  r.kind =
      msg.kind == tacs_graphs::RoomObservation::CORRIDOR ? RoomKind::kCorridor : RoomKind::kRoom;
  for (size_t i = 0; i < r.walls.size(); ++i)
    r.walls[i] = msg.wall_ids[i] >= 0 ? msg.wall_ids[i] : -1;
  r.center = fromPoint(msg.center);
  r.axes_yaw = msg.axes_yaw;
  r.free_space.reserve(msg.free_space.size());
  for (const auto& p : msg.free_space) r.free_space.push_back(fromPoint(p));
  r.keyframe_ids.assign(msg.keyframe_ids.begin(), msg.keyframe_ids.end());
  return room;
}

std::vector<std::pair<uint32_t, uint32_t>> wallToWallPairs(
    const tacs_graphs::RoomObservation& msg) {
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  for (size_t i = 0; i + 1 < msg.wall_to_wall.size(); i += 2) {
    pairs.emplace_back(msg.wall_to_wall[i], msg.wall_to_wall[i + 1]);
  }
  return pairs;
}

tacs_graphs::LoopClosure toLoopClosureMsg(const LoopClosure& loop, int room_id,
                                          const std::string& map_frame, double stamp) {
  tacs_graphs::LoopClosure msg;
  msg.header.stamp.fromSec(stamp);
  msg.header.frame_id = map_frame;
  msg.from_id = loop.from;
  msg.to_id = loop.to;
  msg.relative_pose = toPoseMsg(loop.T_from_to);
  msg.score = loop.score;
  msg.fitness = loop.fitness;
  toMatrixArray(loop.information, &msg.information);
  msg.room_id = room_id;
  return msg;
}

LoopEdge fromLoopClosureMsg(const tacs_graphs::LoopClosure& msg) {
  LoopEdge edge;
  edge.from = msg.from_id;
  edge.to = msg.to_id;
  const Pose3 T = fromPoseMsg(msg.relative_pose);
  edge.position = T.translation();
  edge.orientation = Eigen::Quaterniond(T.rotation()).normalized();
  edge.score = msg.score;
  return edge;
}

tacs_graphs::SceneGraph toSceneGraphMsg(const SceneGraph& graph,
                                        const std::map<uint32_t, uint32_t>& wall_observations,
                                        const std::string& map_frame, double stamp) {
  tacs_graphs::SceneGraph msg;
  msg.header.stamp.fromSec(stamp);
  msg.header.frame_id = map_frame;
  for (const auto& [id, kf] : graph.keyframes) {
    tacs_graphs::SceneGraphKeyframe m;
    m.id = id;
    m.stamp.fromSec(kf.stamp);
    m.pose = toPoseMsg(kf.pose());
    m.room_id = kf.room_id;
    msg.keyframes.push_back(m);
  }
  for (const auto& [id, w] : graph.walls) {
    tacs_graphs::Wall m;
    m.id = id;
    m.normal = toVector(w.normal);
    m.d = w.d;
    m.endpoints[0] = toPoint2(w.endpoints[0]);
    m.endpoints[1] = toPoint2(w.endpoints[1]);
    m.z_min = w.z_range[0];
    m.z_max = w.z_range[1];
    const auto it = wall_observations.find(id);
    m.observation_count = it == wall_observations.end() ? 0 : it->second;
    m.is_wall = w.is_wall;
    msg.walls.push_back(m);
  }
  for (const auto& [id, r] : graph.rooms) {
    tacs_graphs::Room m;
    m.id = id;
    m.kind = r.kind == RoomKind::kCorridor ? tacs_graphs::Room::CORRIDOR : tacs_graphs::Room::ROOM;
    m.wall_ids.fill(-1);
    for (size_t i = 0; i < r.wall_ids.size() && i < m.wall_ids.size(); ++i) {
      m.wall_ids[i] = static_cast<int32_t>(r.wall_ids[i]);
    }
    m.center = toPoint(r.center);
    for (const auto& p : r.free_space) m.free_space.push_back(toPoint2(p));
    m.keyframe_ids.assign(r.keyframe_ids.begin(), r.keyframe_ids.end());
    msg.rooms.push_back(m);
  }
  for (const LoopEdge& l : graph.loops) {
    tacs_graphs::LoopClosure m;
    m.header = msg.header;
    m.from_id = l.from;
    m.to_id = l.to;
    m.relative_pose = toPoseMsg(l.relativePose());
    m.score = l.score;
    m.room_id = -1;
    msg.loops.push_back(m);
  }
  return msg;
}

SceneGraph fromSceneGraphMsg(const tacs_graphs::SceneGraph& msg) {
  SceneGraph graph;
  for (const auto& m : msg.keyframes) {
    KeyframeNode kf;
    kf.id = m.id;
    kf.stamp = m.stamp.toSec();
    kf.setPose(fromPoseMsg(m.pose));
    kf.room_id = m.room_id;
    graph.keyframes[m.id] = kf;
  }
  for (const auto& m : msg.walls) {
    WallNode w;
    w.id = m.id;
    w.normal = fromVector(m.normal);
    w.d = m.d;
    for (int i = 0; i < 2; ++i) w.endpoints[i] = {m.endpoints[i].x, m.endpoints[i].y};
    w.z_range = {m.z_min, m.z_max};
    w.is_wall = m.is_wall;
    graph.walls[m.id] = w;
  }
  for (const auto& m : msg.rooms) {
    RoomNode r;
    r.id = m.id;
    r.kind = m.kind == tacs_graphs::Room::CORRIDOR ? RoomKind::kCorridor : RoomKind::kRoom;
    for (const int32_t id : m.wall_ids) {
      if (id >= 0) r.wall_ids.push_back(static_cast<uint32_t>(id));
    }
    r.center = fromPoint(m.center);
    for (const auto& p : m.free_space) r.free_space.emplace_back(p.x, p.y);
    r.keyframe_ids.assign(m.keyframe_ids.begin(), m.keyframe_ids.end());
    graph.rooms[m.id] = r;
  }
  for (const auto& m : msg.loops) graph.loops.push_back(fromLoopClosureMsg(m));
  return graph;
}

}  // namespace tacs
