// Top-down picture of a world: floors, ground-truth rooms (translucent, labelled), walls (full
// height dark, half walls and rails lighter), boxes and the robot path.
#pragma once

#include <string>

#include "tacs_graphs/sim/robot_path.h"
#include "tacs_graphs/sim/world.h"
#include "tacs_graphs/viz/canvas.h"

namespace tacs::sim {

/// Footprint corners of a wall or a box (counter-clockwise).
Polygon2 wallFootprint(const Wall& wall);
Polygon2 boxFootprint(const Box& box);

/// A canvas covering every floor of `world` plus a margin.
viz::Canvas worldCanvas(const World& world, double resolution_m);

/// Draws the world and, when given, the robot path onto `canvas`.
void drawWorld(const World& world, const RobotPath* path, viz::Canvas* canvas);

}  // namespace tacs::sim
