#include "tacs_graphs/scene_graph/room_floor.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <stdexcept>

namespace tacs {

namespace {

// A row-major grid of cells (x0 + i, y0 + j), i < width, j < height.
struct Grid {
  int64_t x0 = 0, y0 = 0;
  int width = 0, height = 0;
  size_t size() const { return static_cast<size_t>(width) * height; }
  size_t at(int i, int j) const { return static_cast<size_t>(j) * width + i; }
  bool inside(int i, int j) const { return i >= 0 && j >= 0 && i < width && j < height; }
};

// The inner side of a wall that bounds a room: points p with side * normal . (p - on_wall) >= 0.
struct HalfPlane {
  Eigen::Vector2d normal;
  Eigen::Vector2d on_wall;
  double side;
};

std::vector<HalfPlane> innerSides(const RoomNode& room, const SceneGraph& graph) {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const auto& p : room.free_space) centroid += p;
  centroid /= static_cast<double>(room.free_space.size());
  std::vector<HalfPlane> out;
  for (uint32_t id : room.wall_ids) {
    const auto it = graph.walls.find(id);
    if (it == graph.walls.end()) continue;
    const Eigen::Vector2d n = it->second.normal.head<2>();
    if (n.norm() < 0.5) continue;  // not a vertical plane: bounds nothing in 2D
    const Eigen::Vector2d a = it->second.endpoints[0];
    const double side = n.dot(centroid - a) >= 0.0 ? 1.0 : -1.0;
    out.push_back({n.normalized(), a, side});
  }
  return out;
}

// Cells a wall of the building passes through; the floor does not grow across them.
std::vector<uint8_t> wallCells(const SceneGraph& graph, const Grid& grid, double cell) {
  std::vector<uint8_t> blocked(grid.size(), 0);
  for (const auto& [id, w] : graph.walls) {
    if (!w.is_wall) continue;
    const Eigen::Vector2d a = w.endpoints[0], b = w.endpoints[1];
    const int steps = static_cast<int>((b - a).norm() / (cell / 3.0)) + 1;
    for (int s = 0; s <= steps; ++s) {
      const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(s) / steps);
      const int i = static_cast<int>(std::floor(p.x() / cell) - grid.x0);
      const int j = static_cast<int>(std::floor(p.y() / cell) - grid.y0);
      if (grid.inside(i, j)) blocked[grid.at(i, j)] = 1;
    }
  }
  return blocked;
}

}  // namespace

std::map<uint32_t, std::vector<Eigen::Vector2i>> roomFloors(const SceneGraph& graph,
                                                            const RoomFloorConfig& config) {
  if (!(config.cell_m > 0.0) || config.reach_m < 0.0 || config.point_radius_m < 0.0) {
    throw std::invalid_argument("roomFloors: cell_m must be > 0, reach_m and point_radius_m >= 0");
  }
  std::map<uint32_t, std::vector<Eigen::Vector2i>> floors;
  const double cell = config.cell_m;
  Eigen::Vector2d lo(std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
  Eigen::Vector2d hi = -lo;
  std::vector<const RoomNode*> rooms;
  for (const auto& [id, room] : graph.rooms) {
    floors[id];
    if (room.free_space.empty()) continue;
    rooms.push_back(&room);
    for (const auto& p : room.free_space) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  if (rooms.empty()) return floors;
  const double margin = std::max(config.reach_m, config.point_radius_m) + 2.0 * cell;
  Grid grid;
  grid.x0 = static_cast<int64_t>(std::floor((lo.x() - margin) / cell));
  grid.y0 = static_cast<int64_t>(std::floor((lo.y() - margin) / cell));
  grid.width = static_cast<int>(std::floor((hi.x() + margin) / cell) - grid.x0) + 1;
  grid.height = static_cast<int>(std::floor((hi.y() + margin) / cell) - grid.y0) + 1;
  const std::vector<uint8_t> blocked = wallCells(graph, grid, cell);

  // Dijkstra over 8-connected cells from every room's free space at once: each cell learns its
  // nearest room and the path length to it, paths never entering a wall cell.
  std::vector<float> dist(grid.size(), std::numeric_limits<float>::infinity());
  std::vector<int32_t> owner(grid.size(), -1);
  using Item = std::pair<float, size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (size_t k = 0; k < rooms.size(); ++k) {
    for (const auto& p : rooms[k]->free_space) {
      const size_t c = grid.at(static_cast<int>(std::floor(p.x() / cell) - grid.x0),
                               static_cast<int>(std::floor(p.y() / cell) - grid.y0));
      if (owner[c] >= 0) continue;
      dist[c] = 0.0f, owner[c] = static_cast<int32_t>(k);
      queue.push({0.0f, c});
    }
  }
  // The slack keeps a step that lands exactly on the reach (float sums of cells) inside.
  const float reach =
      static_cast<float>(std::max(config.reach_m, config.point_radius_m) + 1e-3 * cell);
  const float straight = static_cast<float>(cell), diagonal = straight * std::sqrt(2.0f);
  while (!queue.empty()) {
    const auto [d, c] = queue.top();
    queue.pop();
    if (d > dist[c]) continue;
    const int i = static_cast<int>(c % grid.width), j = static_cast<int>(c / grid.width);
    for (int di = -1; di <= 1; ++di) {
      for (int dj = -1; dj <= 1; ++dj) {
        if ((di == 0 && dj == 0) || !grid.inside(i + di, j + dj)) continue;
        const size_t n = grid.at(i + di, j + dj);
        if (blocked[n]) continue;
        // A diagonal step may not slip between two wall cells.
        if (di != 0 && dj != 0 && (blocked[grid.at(i + di, j)] || blocked[grid.at(i, j + dj)])) {
          continue;
        }
        const float nd = d + (di != 0 && dj != 0 ? diagonal : straight);
        if (nd > reach || nd >= dist[n]) continue;
        dist[n] = nd, owner[n] = owner[c];
        queue.push({nd, n});
      }
    }
  }

  std::vector<std::vector<HalfPlane>> sides;
  for (const RoomNode* room : rooms) sides.push_back(innerSides(*room, graph));
  for (size_t c = 0; c < grid.size(); ++c) {
    if (owner[c] < 0) continue;
    const int i = static_cast<int>(c % grid.width), j = static_cast<int>(c / grid.width);
    const Eigen::Vector2d centre((grid.x0 + i + 0.5) * cell, (grid.y0 + j + 0.5) * cell);
    bool in = dist[c] <= config.point_radius_m + 1e-3 * cell;
    if (!in) {
      in = true;
      for (const auto& h : sides[owner[c]]) {
        // Half a cell of slack keeps the cells the wall's face passes through.
        if (h.side * h.normal.dot(centre - h.on_wall) < -0.5 * cell) {
          in = false;
          break;
        }
      }
    }
    if (in) floors[rooms[owner[c]]->id].emplace_back(grid.x0 + i, grid.y0 + j);
  }
  return floors;
}

}  // namespace tacs
