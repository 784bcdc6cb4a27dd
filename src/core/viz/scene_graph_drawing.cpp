#include "tacs_graphs/viz/scene_graph_drawing.h"

#include <algorithm>
#include <string>
#include <vector>

#include "tacs_graphs/scene_graph/room_floor.h"

namespace tacs::viz {

Rgba roomColor(uint32_t room_id, uint8_t alpha) {
  static constexpr Rgba kPalette[] = {
      {230, 25, 75},  {60, 180, 75},  {0, 130, 200},  {245, 130, 48}, {145, 30, 180},
      {70, 190, 190}, {240, 50, 230}, {170, 110, 40}, {128, 128, 0},  {0, 0, 128}};
  Rgba c = kPalette[room_id % (sizeof(kPalette) / sizeof(kPalette[0]))];
  c.a = alpha;
  return c;
}

void sceneGraphBounds(const SceneGraph& graph, const PointCloud* map_points, double margin_m,
                      Eigen::Vector2d* min_xy, Eigen::Vector2d* max_xy) {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e18), hi = -lo;
  auto grow = [&](const Eigen::Vector2d& p) { lo = lo.cwiseMin(p), hi = hi.cwiseMax(p); };
  for (const auto& [id, kf] : graph.keyframes) grow(kf.position.head<2>());
  for (const auto& [id, w] : graph.walls) grow(w.endpoints[0]), grow(w.endpoints[1]);
  for (const auto& [id, r] : graph.rooms) {
    for (const auto& p : r.free_space) grow(p);
  }
  if (map_points) {
    for (const auto& p : map_points->points) grow(Eigen::Vector2d(p.x, p.y));
  }
  if (lo.x() > hi.x()) lo.setZero(), hi.setZero();  // an empty graph
  *min_xy = lo - Eigen::Vector2d::Constant(margin_m);
  *max_xy = hi + Eigen::Vector2d::Constant(margin_m);
}

void drawSceneGraph(const SceneGraph& graph, const PointCloud* map_points, Canvas* canvas) {
  if (map_points) {
    // Points between 0.3 m and 2 m above the floor outline the building; floor hits would
    // cover everything in grey.
    for (const auto& p : map_points->points) {
      if (p.z < 0.3f || p.z > 2.0f) continue;
      canvas->fillCircle(Eigen::Vector2d(p.x, p.y), 0.03, {160, 160, 160, 255});
    }
  }
  // Each room's floor (faint) under its free space.
  const RoomFloorConfig floor_config;
  const double cell = floor_config.cell_m;
  for (const auto& [id, cells] : roomFloors(graph, floor_config)) {
    for (const auto& c : cells) {
      const Eigen::Vector2d lo = c.cast<double>() * cell;
      canvas->fillPolygon({lo, lo + Eigen::Vector2d(cell, 0), lo + Eigen::Vector2d(cell, cell),
                           lo + Eigen::Vector2d(0, cell)},
                          roomColor(id, 35));
    }
  }
  for (const auto& [id, room] : graph.rooms) {
    for (const auto& p : room.free_space) canvas->fillCircle(p, 0.12, roomColor(id, 60));
  }
  for (const auto& [id, wall] : graph.walls) {
    // Other planes (furniture seen over, pillar faces) thin and light, under the walls.
    if (wall.is_wall) {
      canvas->drawLine(wall.endpoints[0], wall.endpoints[1], {20, 20, 20, 255}, 3.0);
    } else {
      canvas->drawLine(wall.endpoints[0], wall.endpoints[1], {120, 120, 120, 255}, 1.0);
    }
  }
  for (const auto& [id, room] : graph.rooms) {
    const Eigen::Vector2d c = room.center.head<2>();
    for (uint32_t wall_id : room.wall_ids) {
      const auto it = graph.walls.find(wall_id);
      if (it == graph.walls.end()) continue;
      const Eigen::Vector2d mid = 0.5 * (it->second.endpoints[0] + it->second.endpoints[1]);
      canvas->drawLine(c, mid, roomColor(id, 220), 1.5);
    }
    const double half = room.kind == RoomKind::kRoom ? 0.3 : 0.2;
    canvas->fillPolygon({c + Eigen::Vector2d(-half, -half), c + Eigen::Vector2d(half, -half),
                         c + Eigen::Vector2d(half, half), c + Eigen::Vector2d(-half, half)},
                        roomColor(id, 255));
    canvas->drawText(c + Eigen::Vector2d(half + 0.1, half), std::to_string(id), {0, 0, 0, 255}, 2);
  }
  std::vector<Eigen::Vector2d> path;
  for (const auto& [id, kf] : graph.keyframes) path.push_back(kf.position.head<2>());
  if (path.size() > 1) canvas->drawPolyline(path, {0, 90, 255, 220}, 2.0);
  for (const auto& loop : graph.loops) {
    const auto a = graph.keyframes.find(loop.from), b = graph.keyframes.find(loop.to);
    if (a == graph.keyframes.end() || b == graph.keyframes.end()) continue;
    canvas->drawLine(a->second.position.head<2>(), b->second.position.head<2>(), {255, 140, 0, 255},
                     2.0);
  }
}

}  // namespace tacs::viz
