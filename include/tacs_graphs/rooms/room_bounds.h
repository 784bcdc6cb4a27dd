// Which planes may bound a room. Room extraction (paper Sec. III-B-3) pairs facing planes around
// a free-space region. In an open-plan hall, rows of racks, library stacks or partitions stand
// free of the walls: a region along one aisle would pair the two rack faces and become a room of
// its own, though both ends of the aisle open into the hall it belongs to. So a plane that has
// no wall's shape (WallMap::hasWallShape: too short, seen over, or in front of a taller wall), or
// whose top stays far below the tallest walls' (a rack face seen only from its aisle is never
// seen over), bounds a room only when it is anchored to the walls: one of its ends meets a wall, or
// meets a plane anchored so (a half wall between two rooms, an office's partitions, a cabinet in a
// corner). Free-standing furniture then bounds nothing, and the free space between it joins the
// space around it.
#pragma once

#include <cstdint>
#include <map>

#include "tacs_graphs/rooms/rooms_config.h"
#include "tacs_graphs/walls/wall_map.h"

namespace tacs {

/// The walls of `walls` and the planes anchored to them (see the file comment). Walls: planes of
/// a wall's shape whose mean top is at most `top_margin` below the tallest such plane's (of those
/// at least 4 m long, when there are some) and at least `top_min_share` of its height (1.6 m
/// cubicle partitions under a 3 m ceiling are furniture, though only 1.5 m lower). An end within
/// `anchor_distance` (xy) of an anchored plane's extent anchors a plane. anchor_distance <= 0
/// returns every landmark (each plane may bound a room, as in the paper).
std::map<uint32_t, WallLandmark> roomBoundingPlanes(const WallMap& walls, double anchor_distance,
                                                    double top_margin, double top_min_share);
/// The same with rooms.extraction's anchor_distance_m, wall_top_margin_m, wall_top_min_share.
std::map<uint32_t, WallLandmark> roomBoundingPlanes(const WallMap& walls,
                                                    const RoomExtractionConfig& config);

/// Whether the rule holds: the paper's rooms (method tacs) with anchor_distance_m > 0; the voxel
/// baseline keeps every plane, as S-Graphs+ does.
bool freeStandingFurnitureBoundsNoRoom(const RoomsConfig& config);

}  // namespace tacs
