#include "tacs_graphs/sim/ray_caster.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tacs::sim {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;
}  // namespace

RayCaster::RayCaster(const World& world, double cell_size_m) {
  for (const auto& w : world.walls) {
    const Eigen::Vector2d mid = 0.5 * (w.from + w.to);
    const Eigen::Vector2d dir = w.to - w.from;
    addBox(Eigen::Vector3d(mid.x(), mid.y(), 0.5 * (w.z_min + w.z_max)),
           Eigen::Vector3d(dir.norm(), w.thickness, w.z_max - w.z_min),
           std::atan2(dir.y(), dir.x()), w.reflectivity);
  }
  for (const auto& b : world.boxes)
    addBox(b.center, b.size, b.yaw_deg * kPi / 180.0, b.reflectivity);
  for (const auto* list : {&world.floors, &world.ceilings}) {
    for (const auto& h : *list) {
      Plane p{h.polygon, h.polygon[0], h.polygon[0], h.z, h.reflectivity};
      for (const auto& v : h.polygon) p.lo = p.lo.cwiseMin(v), p.hi = p.hi.cwiseMax(v);
      planes_.push_back(p);
    }
  }
  buildGrid(cell_size_m);
}

void RayCaster::addBox(const Eigen::Vector3d& center, const Eigen::Vector3d& size, double yaw,
                       double reflectivity) {
  boxes_.push_back({center, 0.5 * size, std::cos(yaw), std::sin(yaw), reflectivity});
}

void RayCaster::buildGrid(double cell_size_m) {
  cell_ = cell_size_m;
  // Footprint bounds of every primitive.
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> bounds;
  for (const auto& b : boxes_) {
    const Eigen::Vector2d ext(std::abs(b.c) * b.half.x() + std::abs(b.s) * b.half.y(),
                              std::abs(b.s) * b.half.x() + std::abs(b.c) * b.half.y());
    bounds.emplace_back(b.center.head<2>() - ext, b.center.head<2>() + ext);
  }
  for (const auto& p : planes_) bounds.emplace_back(p.lo, p.hi);
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(kInf), hi = -lo;
  for (const auto& [a, b] : bounds) lo = lo.cwiseMin(a), hi = hi.cwiseMax(b);
  if (bounds.empty()) lo = hi = Eigen::Vector2d::Zero();
  origin_ = lo - Eigen::Vector2d::Constant(1e-3);
  nx_ = std::max(1, static_cast<int>(std::ceil((hi.x() - origin_.x() + 1e-3) / cell_)));
  ny_ = std::max(1, static_cast<int>(std::ceil((hi.y() - origin_.y() + 1e-3) / cell_)));

  // Two passes (count, then fill) into a compact cell -> primitive list.
  std::vector<std::vector<uint32_t>> cells(static_cast<size_t>(nx_) * ny_);
  const double half_cell = 0.5 * cell_;
  for (uint32_t id = 0; id < bounds.size(); ++id) {
    const auto& [a, b] = bounds[id];
    const int x0 = std::clamp(static_cast<int>((a.x() - origin_.x()) / cell_), 0, nx_ - 1);
    const int x1 = std::clamp(static_cast<int>((b.x() - origin_.x()) / cell_), 0, nx_ - 1);
    const int y0 = std::clamp(static_cast<int>((a.y() - origin_.y()) / cell_), 0, ny_ - 1);
    const int y1 = std::clamp(static_cast<int>((b.y() - origin_.y()) / cell_), 0, ny_ - 1);
    for (int iy = y0; iy <= y1; ++iy) {
      for (int ix = x0; ix <= x1; ++ix) {
        if (id < boxes_.size()) {
          // Separating-axis test along the box axes: long diagonal walls skip most cells of
          // their bounding rectangle.
          const OrientedBox& bx = boxes_[id];
          const Eigen::Vector2d d = origin_ +
                                    Eigen::Vector2d((ix + 0.5) * cell_, (iy + 0.5) * cell_) -
                                    bx.center.head<2>();
          const double r = half_cell * (std::abs(bx.c) + std::abs(bx.s));
          if (std::abs(bx.c * d.x() + bx.s * d.y()) > bx.half.x() + r) continue;
          if (std::abs(-bx.s * d.x() + bx.c * d.y()) > bx.half.y() + r) continue;
        }
        cells[static_cast<size_t>(iy) * nx_ + ix].push_back(id);
      }
    }
  }
  cell_start_.assign(cells.size() + 1, 0);
  for (size_t i = 0; i < cells.size(); ++i) {
    cell_start_[i + 1] = cell_start_[i] + cells[i].size();
    prim_ids_.insert(prim_ids_.end(), cells[i].begin(), cells[i].end());
  }
  marks_ = newMarks();
}

bool RayCaster::hitBox(const OrientedBox& b, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                       double t_max, RayHit* hit) const {
  // Slab test in the box frame.
  const Eigen::Vector3d rel = o - b.center;
  const double lo[3] = {b.c * rel.x() + b.s * rel.y(), -b.s * rel.x() + b.c * rel.y(), rel.z()};
  const double ld[3] = {b.c * d.x() + b.s * d.y(), -b.s * d.x() + b.c * d.y(), d.z()};
  double t_near = -kInf, t_far = kInf;
  int axis = -1;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(ld[k]) < 1e-12) {
      if (std::abs(lo[k]) > b.half[k]) return false;
      continue;
    }
    const double inv = 1.0 / ld[k];
    double t0 = (-b.half[k] - lo[k]) * inv, t1 = (b.half[k] - lo[k]) * inv;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > t_near) t_near = t0, axis = k;
    t_far = std::min(t_far, t1);
    if (t_near > t_far) return false;
  }
  // An origin inside the box sees nothing of it (the sensor never starts inside a solid).
  if (axis < 0 || t_near <= 0.0 || t_near >= t_max) return false;
  const double sign = ld[axis] > 0 ? -1.0 : 1.0;
  hit->range = t_near;
  if (axis == 2) {
    hit->normal = Eigen::Vector3d(0, 0, sign);
  } else if (axis == 0) {
    hit->normal = Eigen::Vector3d(sign * b.c, sign * b.s, 0);
  } else {
    hit->normal = Eigen::Vector3d(-sign * b.s, sign * b.c, 0);
  }
  hit->reflectivity = b.reflectivity;
  return true;
}

bool RayCaster::hitPlane(const Plane& p, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                         double t_max, RayHit* hit) const {
  if (std::abs(d.z()) < 1e-12) return false;
  const double t = (p.z - o.z()) / d.z();
  if (t <= 0.0 || t >= t_max) return false;
  const Eigen::Vector2d q = o.head<2>() + t * d.head<2>();
  if ((q.array() < p.lo.array()).any() || (q.array() > p.hi.array()).any()) return false;
  if (!pointInPolygon(p.polygon, q)) return false;
  hit->range = t;
  hit->normal = Eigen::Vector3d(0, 0, d.z() > 0 ? -1.0 : 1.0);
  hit->reflectivity = p.reflectivity;
  return true;
}

bool RayCaster::hitPrimitive(uint32_t id, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                             double t_max, RayHit* hit) const {
  return id < boxes_.size() ? hitBox(boxes_[id], o, d, t_max, hit)
                            : hitPlane(planes_[id - boxes_.size()], o, d, t_max, hit);
}

bool RayCaster::cast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double max_range,
                     RayHit* hit, Marks* marks) const {
  // Clip the ray to the grid rectangle.
  double t_enter = 0.0, t_exit = max_range;
  const Eigen::Vector2d grid_hi = origin_ + cell_ * Eigen::Vector2d(nx_, ny_);
  for (int k = 0; k < 2; ++k) {
    if (std::abs(d[k]) < 1e-12) {
      if (o[k] < origin_[k] || o[k] > grid_hi[k]) return false;
      continue;
    }
    double t0 = (origin_[k] - o[k]) / d[k], t1 = (grid_hi[k] - o[k]) / d[k];
    if (t0 > t1) std::swap(t0, t1);
    t_enter = std::max(t_enter, t0);
    t_exit = std::min(t_exit, t1);
  }
  if (t_enter > t_exit) return false;

  std::vector<uint32_t>& mailbox = marks->mailbox;
  if (++marks->ray_id == 0) {  // wrapped: clear the marks
    std::fill(mailbox.begin(), mailbox.end(), 0);
    marks->ray_id = 1;
  }
  const Eigen::Vector2d p = (o.head<2>() + t_enter * d.head<2>() - origin_) / cell_;
  int ix = std::clamp(static_cast<int>(p.x()), 0, nx_ - 1);
  int iy = std::clamp(static_cast<int>(p.y()), 0, ny_ - 1);
  const int step_x = d.x() > 0 ? 1 : -1, step_y = d.y() > 0 ? 1 : -1;
  const double dt_x = std::abs(d.x()) < 1e-12 ? kInf : cell_ / std::abs(d.x());
  const double dt_y = std::abs(d.y()) < 1e-12 ? kInf : cell_ / std::abs(d.y());
  double next_x = std::abs(d.x()) < 1e-12
                      ? kInf
                      : (origin_.x() + (ix + (step_x > 0 ? 1 : 0)) * cell_ - o.x()) / d.x();
  double next_y = std::abs(d.y()) < 1e-12
                      ? kInf
                      : (origin_.y() + (iy + (step_y > 0 ? 1 : 0)) * cell_ - o.y()) / d.y();
  double best = max_range;
  bool found = false;
  RayHit candidate;
  while (true) {
    const size_t cell = static_cast<size_t>(iy) * nx_ + ix;
    for (uint32_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
      const uint32_t id = prim_ids_[k];
      if (mailbox[id] == marks->ray_id) continue;
      mailbox[id] = marks->ray_id;
      if (hitPrimitive(id, o, d, best, &candidate)) {
        best = candidate.range;
        *hit = candidate;
        found = true;
      }
    }
    const double cell_exit = std::min(next_x, next_y);
    if (best <= cell_exit || cell_exit >= t_exit) break;
    if (next_x < next_y) {
      ix += step_x;
      next_x += dt_x;
      if (ix < 0 || ix >= nx_) break;
    } else {
      iy += step_y;
      next_y += dt_y;
      if (iy < 0 || iy >= ny_) break;
    }
  }
  return found;
}

}  // namespace tacs::sim
