// Core structures <-> the tacs_graphs messages exchanged by the nodes (msg/*.msg): keyframes,
// wall observations, traversable graphs, room observations, loop closures and the scene graph.
#pragma once

#include <tacs_graphs/Keyframe.h>
#include <tacs_graphs/LoopClosure.h>
#include <tacs_graphs/RoomObservation.h>
#include <tacs_graphs/SceneGraph.h>
#include <tacs_graphs/TraversableGraph.h>
#include <tacs_graphs/WallObservation.h>

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "tacs_graphs/common/types.h"
#include "tacs_graphs/loop_closure/loop_detector.h"
#include "tacs_graphs/rooms/room_map.h"
#include "tacs_graphs/scene_graph/scene_graph.h"
#include "tacs_graphs/traversability/traversability_mapper.h"
#include "tacs_graphs/walls/wall_segment.h"

namespace tacs {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// A keyframe as the odometry publishes it; `cloud` and `sensor_in_base` are in the base frame.
tacs_graphs::Keyframe toKeyframeMsg(uint32_t id, double stamp, const Pose3& T_odom_base,
                                    const Matrix6d& information, const PointCloud& cloud,
                                    const Eigen::Vector3d& sensor_in_base,
                                    const std::string& odom_frame, const std::string& base_frame);

tacs_graphs::WallObservation toWallObservationMsg(const WallSegment& wall);
WallSegment fromWallObservationMsg(const tacs_graphs::WallObservation& msg);

/// The per-keyframe traversable graph (in the ground frame T_base_ground of the keyframe) with
/// its keyframe id and odometry pose.
tacs_graphs::TraversableGraph toTraversableGraphMsg(const TravGraph& graph, uint32_t keyframe_id,
                                                    const Pose3& T_odom_base,
                                                    const std::string& base_frame, double stamp,
                                                    const Pose3& T_base_ground = Pose3::Identity());
/// The traversable graph of a keyframe (ground frame, the message's ground_in_base), node flags
/// `traversable` and `safe` included: the TraversableMap builds free space from them.
TravGraph fromTraversableGraphMsg(const tacs_graphs::TraversableGraph& msg);

/// A mapped room of the room segmenter and what room merging did with the observation that
/// updated it now (re-detection, wall-to-wall edges).
tacs_graphs::RoomObservation toRoomObservationMsg(const MappedRoom& room,
                                                  const RoomAssociation& association);
/// The mapped room carried by a room observation (wall categories kept, -1 when absent). Its
/// overlap cells are not carried: they stay empty.
MappedRoom fromRoomObservationMsg(const tacs_graphs::RoomObservation& msg);
/// The wall-to-wall edges (mapped room wall, observed wall) of a room observation; a trailing
/// unpaired id is ignored.
std::vector<std::pair<uint32_t, uint32_t>> wallToWallPairs(const tacs_graphs::RoomObservation& msg);

/// A loop closure of the loop detector; `room_id` is the room that triggered it (-1: distance
/// baseline).
tacs_graphs::LoopClosure toLoopClosureMsg(const LoopClosure& loop, int room_id,
                                          const std::string& map_frame, double stamp);

/// The loop edge carried by a loop-closure message (its information goes to the backend apart).
LoopEdge fromLoopClosureMsg(const tacs_graphs::LoopClosure& msg);

/// The scene graph message; `wall_observations` gives Wall.observation_count (0 when absent).
tacs_graphs::SceneGraph toSceneGraphMsg(const SceneGraph& graph,
                                        const std::map<uint32_t, uint32_t>& wall_observations,
                                        const std::string& map_frame, double stamp);
/// Inverse of toSceneGraphMsg (observation counts and loop information are dropped).
SceneGraph fromSceneGraphMsg(const tacs_graphs::SceneGraph& msg);

}  // namespace tacs
