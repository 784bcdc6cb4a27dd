#include "tacs_graphs/sim/world_drawing.h"

#include <cmath>

namespace tacs::sim {
namespace {

Polygon2 rectangle(const Eigen::Vector2d& center, double half_x, double half_y, double yaw) {
  const Eigen::Vector2d u(std::cos(yaw), std::sin(yaw)), v(-u.y(), u.x());
  return {center - half_x * u - half_y * v, center + half_x * u - half_y * v,
          center + half_x * u + half_y * v, center - half_x * u + half_y * v};
}

constexpr viz::Rgba kRoomColors[] = {{230, 25, 75, 70},  {60, 180, 75, 70},  {0, 130, 200, 70},
                                     {245, 130, 48, 70}, {145, 30, 180, 70}, {70, 190, 190, 70},
                                     {240, 50, 230, 70}, {170, 110, 40, 70}, {128, 128, 0, 70},
                                     {0, 0, 128, 70}};

}  // namespace

Polygon2 wallFootprint(const Wall& w) {
  const Eigen::Vector2d d = w.to - w.from;
  return rectangle(0.5 * (w.from + w.to), 0.5 * d.norm(), 0.5 * w.thickness,
                   std::atan2(d.y(), d.x()));
}

Polygon2 boxFootprint(const Box& b) {
  return rectangle(b.center.head<2>(), 0.5 * b.size.x(), 0.5 * b.size.y(),
                   b.yaw_deg * 3.14159265358979323846 / 180.0);
}

viz::Canvas worldCanvas(const World& world, double resolution_m) {
  Eigen::Vector2d lo = world.floors.at(0).polygon.at(0), hi = lo;
  for (const auto& f : world.floors) {
    for (const auto& p : f.polygon) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  for (const auto& w : world.walls) {
    for (const auto& p : wallFootprint(w)) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  const Eigen::Vector2d margin = Eigen::Vector2d::Constant(1.0);
  return viz::Canvas(lo - margin, hi + margin, resolution_m);
}

void drawWorld(const World& world, const RobotPath* path, viz::Canvas* canvas) {
  for (const auto& f : world.floors) {
    // Lower floors (seen through a drop-off) darker.
    canvas->fillPolygon(f.polygon,
                        f.z < -0.5 ? viz::Rgba{200, 200, 215, 255} : viz::Rgba{238, 238, 238, 255});
  }
  size_t k = 0;
  for (const auto& room : world.rooms) {
    const viz::Rgba c = kRoomColors[k++ % (sizeof(kRoomColors) / sizeof(kRoomColors[0]))];
    canvas->fillPolygon(room.polygon, c);
    canvas->drawPolyline(room.polygon, {c.r, c.g, c.b, 200}, 1.0, true);
  }
  for (const auto& b : world.boxes) {
    const Polygon2 fp = boxFootprint(b);
    const bool overhead = b.center.z() - 0.5 * b.size.z() > 1.0;  // cabinets, pipes
    canvas->fillPolygon(fp, overhead ? viz::Rgba{150, 110, 60, 110} : viz::Rgba{150, 110, 60, 230});
    canvas->drawPolyline(fp, {90, 60, 30, 255}, 1.0, true);
  }
  for (const auto& w : world.walls) {
    const bool full = w.z_min <= 0.05 && w.z_max >= 2.0;
    canvas->fillPolygon(wallFootprint(w),
                        full ? viz::Rgba{30, 30, 30, 255} : viz::Rgba{110, 110, 200, 255});
  }
  if (path) {
    std::vector<Eigen::Vector2d> pts;
    for (size_t i = 0; i < path->samples().size(); i += 5)
      pts.push_back(path->samples()[i].head<2>());
    pts.push_back(path->samples().back().head<2>());
    canvas->drawPolyline(pts, {0, 90, 255, 200}, 2.0);
    canvas->fillCircle(pts.front(), 0.25, {0, 170, 0, 255});
    canvas->drawCircle(pts.back(), 0.35, {220, 0, 0, 255}, 2.0);
  }
  for (const auto& room : world.rooms) {
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (const auto& p : room.polygon) c += p;
    c /= room.polygon.size();
    canvas->drawText(c, room.id, {0, 0, 0, 255}, 2);
  }
}

}  // namespace tacs::sim
