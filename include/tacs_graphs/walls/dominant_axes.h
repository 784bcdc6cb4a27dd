// The building's dominant axes and the x+/x-/y+/y- classification of walls (paper Sec. III-B-1).
//
// The paper splits walls into x- and y-direction planes by their dominant normal component in
// the map frame, which assumes the building is aligned with the map axes. Here the axes are
// estimated from the walls themselves: wall normal angles folded modulo 90 deg, accumulated in a
// histogram weighted by wall length, smoothed, and the peak refined by a circular mean. A robot
// that starts at 30 deg to the walls gets yaw = 30 deg and the same classification as an aligned
// one.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "tacs_graphs/walls/wall_segment.h"

namespace tacs {

class WallMap;

struct DominantAxesConfig {
  /// Histogram bin width (deg).
  double bin_deg = 1.0;
  /// Standard deviation of the Gaussian smoothing of the histogram (deg).
  double smoothing_deg = 2.0;
  /// Walls within this angle of the peak (mod 90 deg) refine the estimate (deg).
  double window_deg = 7.0;
  /// Total wall length (m) needed before the estimate is reported valid.
  double min_support = 3.0;

  template <class V>
  void visit(V& v) {
    v("bin_deg", bin_deg);
    v("smoothing_deg", smoothing_deg);
    v("window_deg", window_deg);
    v("min_support_m", min_support);
  }
  /// Throws ConfigError naming the field ("walls.axes.<field>").
  void validate() const;
};

struct DominantAxes {
  /// Yaw of the building x axis in the frame of the walls (rad), in [-pi/4, pi/4).
  double yaw = 0.0;
  /// Total length (m) of the walls within window_deg of the axes.
  double support = 0.0;
  /// Share of the total wall length that agrees with the axes, in [0, 1].
  double agreement = 0.0;
  /// False when there was too little wall length (yaw is then 0: the frame's own axes).
  bool valid = false;

  Eigen::Vector2d xAxis() const;
  Eigen::Vector2d yAxis() const;
};

/// Estimates the axes from (normal, weight) pairs; only the horizontal part of normals is used.
DominantAxes estimateDominantAxes(const std::vector<Eigen::Vector3d>& normals,
                                  const std::vector<double>& weights,
                                  const DominantAxesConfig& config = {});
/// From wall segments, weighted by length.
DominantAxes estimateDominantAxes(const std::vector<WallSegment>& walls,
                                  const DominantAxesConfig& config = {});
/// From the landmarks of a wall map, weighted by length.
DominantAxes estimateDominantAxes(const WallMap& map, const DominantAxesConfig& config = {});

/// Facing direction of a wall in the building frame: kXPlus when the normal's dominant
/// component along the building axes is +x, and so on. A wall seen from inside a room faces the
/// room, so the room's wall at low x is kXPlus and its wall at high x is kXMinus.
enum class WallDirection { kXPlus, kXMinus, kYPlus, kYMinus };

WallDirection classifyWall(const Eigen::Vector3d& normal, const DominantAxes& axes);

/// True for kXPlus and kXMinus (x-direction planes, paper's Pi_x).
inline bool isXDirection(WallDirection d) {
  return d == WallDirection::kXPlus || d == WallDirection::kXMinus;
}

/// "x+", "x-", "y+" or "y-".
const char* toString(WallDirection d);

}  // namespace tacs
