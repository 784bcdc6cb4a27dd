// A room's floor: the area of the building a room stands for, as grid cells.
//
// A room node holds the traversable nodes it was segmented from (RoomNode::free_space). They keep
// a clearance from walls and furniture and leave out the floor under desks, racks and cubicles, so
// they cover only part of the room. Its floor is that free space extended towards the room's own
// walls: every cell within `reach_m` of the free space along a path that crosses no wall, on the
// inner side of each wall that bounds the room (the side of its free space's centroid), and
// nearer to this room's free space than to any other room's. The free space itself (each point
// with a disc of `point_radius_m`) always belongs to its room.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <vector>

#include "tacs_graphs/scene_graph/scene_graph.h"

namespace tacs {

struct RoomFloorConfig {
  double cell_m = 0.1;           // grid cell; cells are floor(x / cell_m), floor(y / cell_m)
  double point_radius_m = 0.25;  // disc each free-space point always covers
  double reach_m = 1.6;          // how far the floor extends from the free space
};

/// Cell indices (ix, iy) of each room's floor, by room id, in the graph's map frame.
std::map<uint32_t, std::vector<Eigen::Vector2i>> roomFloors(const SceneGraph& graph,
                                                            const RoomFloorConfig& config);

}  // namespace tacs
