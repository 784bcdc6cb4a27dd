// Internal building block of WallExtractor: where a wall face starts, for
// walls.extraction.max_wall_bottom_m. Not part of the public interface.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace tacs::walls {

// The bottom of a run of a vertical plane's inliers (`run` indexes `pts`; the face runs along
// `axis` from t_min to t_max, measured from `c`): the lowest height band joined to the top band
// without a vertical gap of more than a metre, counting only bands whose inliers spread along over
// a third of the face's length. A face hanging from the ceiling (a beam, the step between two
// ceiling heights) keeps its true bottom although its plane takes in the floor points along its
// line, the vertical strip where it crosses a wall, and a few stray returns between (dust, a lamp's
// cable).
double connectedBottom(const std::vector<Eigen::Vector3f>& pts, const std::vector<uint32_t>& run,
                       const Eigen::Vector2d& axis, const Eigen::Vector3d& c, double t_min,
                       double t_max);

}  // namespace tacs::walls
