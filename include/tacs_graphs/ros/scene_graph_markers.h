// rviz drawing of the scene graph and of traversable graphs (visualization_msgs/MarkerArray).
//
// Namespaces (each can be toggled in rviz): keyframes, trajectory, walls, other_planes (plane
// landmarks that are no walls: furniture seen over, pillar faces), rooms, room_walls, loops, and
// traversable_graph for the per-keyframe graphs; matched_rooms for a prior map's re-observed rooms.
#pragma once

#include <visualization_msgs/MarkerArray.h>

#include <map>
#include <string>

#include "tacs_graphs/common/types.h"
#include "tacs_graphs/scene_graph/scene_graph.h"
#include "tacs_graphs/traversability/traversability_mapper.h"

namespace tacs {

/// Keyframes as spheres, the trajectory as a line strip, walls as thin boxes over their extent and
/// height, rooms as flat squares at their centres joined to their walls by lines, loop edges as
/// lines. The first marker is a DELETEALL so that merged walls and rooms disappear.
visualization_msgs::MarkerArray sceneGraphMarkers(const SceneGraph& graph, const std::string& frame,
                                                  double stamp);

/// A prior map (relocalization/prior_session.h) in rviz: its scene graph as sceneGraphMarkers()
/// draws it, in `frame` (the prior's map frame), plus the prior rooms the session re-observed
/// (`room_pairs`, session id -> prior id) as tall green pillars labelled "prior P = room S"
/// (namespace matched_rooms).
visualization_msgs::MarkerArray priorMapMarkers(const SceneGraph& prior,
                                                const std::map<uint32_t, uint32_t>& room_pairs,
                                                const std::string& frame, double stamp);

/// The traversable (green) and safe (dark green) edges of one keyframe graph moved by
/// T_frame_base; the marker id is the keyframe id so that graphs accumulate in rviz.
visualization_msgs::Marker traversableGraphMarker(const TravGraph& graph_in_base,
                                                  const Pose3& T_frame_base, uint32_t keyframe_id,
                                                  const std::string& frame, double stamp);

}  // namespace tacs
