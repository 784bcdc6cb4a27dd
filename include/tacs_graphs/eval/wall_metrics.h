// Wall precision against ground truth (issue "open-plan interiors"): how many of the scene graph's
// walls lie on a wall of the world rather than on furniture (a rack face, a cubicle partition, a
// book stack). An estimated wall (WallNode::is_wall, world frame) is correct when it lies on a
// face of a ground-truth wall: normals within `max_angle_deg`, both of its ends within
// `max_distance` of that face's line, and at least `min_overlap` of its length over the face's
// extent. Plane landmarks that are no walls are not scored.
#pragma once

#include <cstddef>
#include <vector>

#include "tacs_graphs/scene_graph/scene_graph.h"
#include "tacs_graphs/sim/world.h"

namespace tacs {

struct WallMetricsConfig {
  double max_angle_deg = 10.0;  // [deg]
  double max_distance = 0.25;   // [m] from the face's line, each end
  double min_overlap = 0.5;     // share of the estimated wall's length over the face [-]
};

struct WallMetrics {
  size_t walls = 0;    // estimated walls (is_wall)
  size_t correct = 0;  // ... on a ground-truth wall face
  double precision() const { return walls ? static_cast<double>(correct) / walls : 1.0; }
};

/// Scores the walls of `graph` (world frame, transformSceneGraph) against `ground_truth`.
WallMetrics evaluateWalls(const SceneGraph& graph, const std::vector<sim::Wall>& ground_truth,
                          const WallMetricsConfig& config = {});

}  // namespace tacs
