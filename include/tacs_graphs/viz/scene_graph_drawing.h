// Top-down picture of a scene graph (topdown.png of the run folder): map points, rooms as
// translucent free space with their centre and room-wall lines, walls, the keyframe trajectory and
// loop edges.
#pragma once

#include "tacs_graphs/common/types.h"
#include "tacs_graphs/scene_graph/scene_graph.h"
#include "tacs_graphs/viz/canvas.h"

namespace tacs::viz {

/// A distinct translucent colour per room id.
Rgba roomColor(uint32_t room_id, uint8_t alpha = 90);

/// The xy box holding every keyframe, wall endpoint and free-space node (and the map points when
/// given), plus `margin_m`.
void sceneGraphBounds(const SceneGraph& graph, const PointCloud* map_points, double margin_m,
                      Eigen::Vector2d* min_xy, Eigen::Vector2d* max_xy);

/// Draws onto `canvas`; `map_points` (map frame) may be null.
void drawSceneGraph(const SceneGraph& graph, const PointCloud* map_points, Canvas* canvas);

}  // namespace tacs::viz
