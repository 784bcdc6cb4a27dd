// A synthetic floor plan for the room tests: walls as 2D segments of zero thickness, a
// traversable graph on a 0.2 m grid over the free floor (clearance = distance to the nearest
// wall, edges never cross a wall) and the wall landmarks (one per wall face, normal facing the
// side it is seen from).
//
// twoRoomsAndCorridor(): room A [0,5]x[0,4], room B [5,10]x[0,4], corridor [-2,12]x[4,6] with
// open ends (no end walls); doors of `door` metres in the wall y = 4 at x = 2 and x = 7.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include "tacs_graphs/traversability/traversable_map.h"
#include "tacs_graphs/walls/wall_map.h"
#include "tacs_graphs/walls/wall_segment.h"

namespace tacs::test {

struct Segment2 {
  Eigen::Vector2d a, b;
};

inline double distanceToSegment(const Eigen::Vector2d& p, const Segment2& s) {
  const Eigen::Vector2d ab = s.b - s.a;
  const double t = std::clamp((p - s.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (s.a + t * ab - p).norm();
}

inline bool crosses(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Segment2& s) {
  const auto cr = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
    return u.x() * v.y() - u.y() * v.x();
  };
  const double d1 = cr(s.b - s.a, p - s.a), d2 = cr(s.b - s.a, q - s.a);
  const double d3 = cr(q - p, s.a - p), d4 = cr(q - p, s.b - p);
  return d1 * d2 < 0 && d3 * d4 < 0;
}

struct FloorPlan {
  std::vector<Segment2> walls;
  Eigen::Vector2d lo, hi;  // floor extent
  /// Rectangles (min, max) without floor.
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> voids;
  /// Wall faces seen as observations (map frame), one WallSegment per face.
  std::vector<WallSegment> faces;

  /// A wall from a to b; `faces_seen`: +1 the face on the left of a->b, -1 the right, 0 both.
  void wall(Eigen::Vector2d a, Eigen::Vector2d b, int faces_seen = 0) {
    walls.push_back({a, b});
    const Eigen::Vector2d dir = (b - a).normalized();
    const Eigen::Vector2d left(-dir.y(), dir.x());
    for (int side : {1, -1}) {
      if (faces_seen != 0 && faces_seen != side) continue;
      WallSegment w;
      w.normal = Eigen::Vector3d(side * left.x(), side * left.y(), 0.0);
      w.d = -w.normal.head<2>().dot(a);
      const Eigen::Vector2d axis = wallAxis(w.normal);
      w.endpoints[0] = (b - a).dot(axis) > 0 ? a : b;
      w.endpoints[1] = (b - a).dot(axis) > 0 ? b : a;
      w.z_min = 0.0;
      w.z_max = 2.5;
      w.inliers = 400;
      faces.push_back(w);
    }
  }

  /// The traversable graph (map frame) on a `step` grid, as one keyframe graph at identity.
  TravGraph graph(double step = 0.2) const {
    TravGraph g;
    const int nx = static_cast<int>(std::round((hi.x() - lo.x()) / step));
    const int ny = static_cast<int>(std::round((hi.y() - lo.y()) / step));
    std::vector<int> index(static_cast<size_t>(nx) * ny, -1);
    for (int i = 0; i < nx; ++i) {
      for (int j = 0; j < ny; ++j) {
        const Eigen::Vector2d p = lo + Eigen::Vector2d((i + 0.5) * step, (j + 0.5) * step);
        bool in_void = false;
        for (const auto& [vlo, vhi] : voids) {
          in_void =
              in_void || (p.x() > vlo.x() && p.x() < vhi.x() && p.y() > vlo.y() && p.y() < vhi.y());
        }
        if (in_void) continue;
        double clearance = std::numeric_limits<double>::infinity();
        for (const auto& w : walls) clearance = std::min(clearance, distanceToSegment(p, w));
        if (clearance < 0.15) continue;  // inside a wall's footprint
        TravNode n;
        n.position = Eigen::Vector3d(p.x(), p.y(), 0.0);
        n.label = TravLabel::kGround;
        n.traversable = true;
        n.clearance = static_cast<float>(clearance);
        index[static_cast<size_t>(i) * ny + j] = static_cast<int>(g.nodes.size());
        g.nodes.push_back(n);
      }
    }
    const auto link = [&](int i0, int j0, int i1, int j1) {
      if (i1 >= nx || j1 >= ny) return;
      const int a = index[static_cast<size_t>(i0) * ny + j0];
      const int b = index[static_cast<size_t>(i1) * ny + j1];
      if (a < 0 || b < 0) return;
      for (const auto& w : walls) {
        if (crosses(g.nodes[a].position.head<2>(), g.nodes[b].position.head<2>(), w)) return;
      }
      g.edges.emplace_back(a, b);
    };
    for (int i = 0; i < nx; ++i) {
      for (int j = 0; j < ny; ++j) {
        link(i, j, i + 1, j);
        link(i, j, i, j + 1);
      }
    }
    return g;
  }

  /// A traversable map holding the whole plan as keyframe 0.
  TraversableMap map(const TraversabilityConfig& config = {}) const {
    TraversableMap m(config);
    m.insert(graph(), Pose3::Identity(), 0);
    return m;
  }

  /// A wall map holding every face (observed from the identity pose).
  WallMap wallMap() const {
    WallMap m;
    m.associate(faces, Pose3::Identity());
    return m;
  }
};

inline FloorPlan twoRoomsAndCorridor(double door = 1.0) {
  FloorPlan p;
  p.lo = {-2.0, 0.0};
  p.hi = {12.0, 6.0};
  p.wall({0, 0}, {10, 0}, 1);   // south, seen from the north (inside)
  p.wall({0, 0}, {0, 4}, -1);   // west of room A, seen from the east
  p.wall({10, 0}, {10, 4}, 1);  // east of room B, seen from the west
  p.wall({5, 0}, {5, 4});       // partition
  // y = 4 with two doors: [0,2], [2+door, 7], [7+door, 10].
  p.wall({0, 4}, {2, 4});
  p.wall({2 + door, 4}, {7, 4});
  p.wall({7 + door, 4}, {10, 4});
  p.wall({-2, 6}, {12, 6}, -1);  // north of the corridor, seen from the south
  // The corridor's floor outside the rooms: walls below it where no room is.
  p.wall({-2, 4}, {0, 4}, 1);
  p.wall({10, 4}, {12, 4}, 1);
  p.voids = {{{-2, 0}, {0, 4}}, {{10, 0}, {12, 4}}};
  return p;
}

}  // namespace tacs::test
