// Ray casting against the primitives of a World, accelerated by a 2D uniform grid over x/y:
// walls and boxes are boxes rotated about z, floors and ceilings horizontal polygons. A ray walks
// the grid cells it crosses (Amanatides-Woo traversal) and stops as soon as the nearest hit lies
// within the current cell.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "tacs_graphs/sim/world.h"

namespace tacs::sim {

struct RayHit {
  double range = 0.0;                                 // [m] along the unit direction
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // surface normal facing the ray origin
  double reflectivity = 0.0;
};

class RayCaster {
 public:
  /// `cell_size_m`: grid pitch; about the size of a door or a piece of furniture works best.
  explicit RayCaster(const World& world, double cell_size_m = 1.0);

  /// Per-primitive "already tested" marks of one ray after another: a primitive spanning several
  /// grid cells is tested once per ray. One per thread.
  struct Marks {
    std::vector<uint32_t> mailbox;
    uint32_t ray_id = 0;
  };
  Marks newMarks() const { return Marks{std::vector<uint32_t>(primitiveCount(), 0), 0}; }

  /// Nearest hit along origin + t * direction for t in (0, max_range]. `direction` must be unit.
  /// Threads casting at once each pass their own `marks` (newMarks()).
  bool cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double max_range,
            RayHit* hit, Marks* marks) const;
  /// The same with the caster's own marks: not thread-safe.
  bool cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double max_range,
            RayHit* hit) const {
    return cast(origin, direction, max_range, hit, &marks_);
  }

  size_t primitiveCount() const { return boxes_.size() + planes_.size(); }

 private:
  struct OrientedBox {
    Eigen::Vector3d center;
    Eigen::Vector3d half;
    double c, s;  // cos, sin of yaw
    double reflectivity;
  };
  struct Plane {
    Polygon2 polygon;
    Eigen::Vector2d lo, hi;  // bounding box
    double z;
    double reflectivity;
  };

  void addBox(const Eigen::Vector3d& center, const Eigen::Vector3d& size, double yaw_rad,
              double reflectivity);
  void buildGrid(double cell_size_m);
  bool hitBox(const OrientedBox& b, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
              double t_max, RayHit* hit) const;
  bool hitPlane(const Plane& p, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_max,
                RayHit* hit) const;
  bool hitPrimitive(uint32_t id, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_max,
                    RayHit* hit) const;

  std::vector<OrientedBox> boxes_;  // primitive ids 0..boxes_.size()-1
  std::vector<Plane> planes_;       // then ids boxes_.size()...
  // Grid: cell (ix, iy) holds prim_ids_[cell_start_[i] .. cell_start_[i + 1]), i = iy * nx_ + ix.
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_ = 1.0;
  int nx_ = 0, ny_ = 0;
  std::vector<uint32_t> cell_start_;
  std::vector<uint32_t> prim_ids_;
  mutable Marks marks_;
};

}  // namespace tacs::sim
