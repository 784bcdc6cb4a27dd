// Imaginary partitions of a large room (paper Sec. III-D, Fig. 5(a)): the room is cut into
// pieces of length L_part along its long axis, and a re-detection searches only the two
// partitions whose centres are nearest to the query, closer than L_part.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace tacs {

struct RoomPartitions {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // mean of the room's positions
  Eigen::Vector2d axis = Eigen::Vector2d::UnitX();   // long axis (unit)
  double s_min = 0.0, s_max = 0.0;                   // extent along the axis [m]
  std::vector<double> centers;                       // partition centres along the axis [m]
  std::vector<int> index_of;                         // partition of each input position
  std::vector<int> selected;                         // searched partitions, nearest first
};

/// Splits the positions (the room's keyframes, map frame xy) into partitions of length
/// `partition_length` along their principal axis (one partition when the extent is shorter) and
/// selects up to two partitions whose centres lie within `partition_length` of the query along
/// the axis; when none does, the nearest one.
RoomPartitions partitionRoom(const std::vector<Eigen::Vector2d>& positions,
                             const Eigen::Vector2d& query, double partition_length);

}  // namespace tacs
