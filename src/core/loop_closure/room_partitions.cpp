#include "tacs_graphs/loop_closure/room_partitions.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>

namespace tacs {

RoomPartitions partitionRoom(const std::vector<Eigen::Vector2d>& positions,
                             const Eigen::Vector2d& query, double partition_length) {
  RoomPartitions out;
  if (positions.empty()) return out;
  for (const auto& p : positions) out.origin += p;
  out.origin /= static_cast<double>(positions.size());
  // Long axis: principal direction of the positions. The room's keyframes cover its free space
  // along the path, which is what the search needs to cut.
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const auto& p : positions) scatter += (p - out.origin) * (p - out.origin).transpose();
  if (positions.size() >= 2 && scatter.trace() > 1e-12) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(scatter);
    out.axis = eig.eigenvectors().col(1).normalized();
  }
  // A fixed sign, so partition 0 is always at the same end of the room.
  if (out.axis.x() < -1e-9 || (std::abs(out.axis.x()) <= 1e-9 && out.axis.y() < 0.0)) {
    out.axis = -out.axis;
  }
  std::vector<double> s(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) s[i] = out.axis.dot(positions[i] - out.origin);
  out.s_min = *std::min_element(s.begin(), s.end());
  out.s_max = *std::max_element(s.begin(), s.end());
  const double extent = out.s_max - out.s_min;
  const int count = std::max(1, static_cast<int>(std::ceil(extent / partition_length - 1e-9)));
  for (int k = 0; k < count; ++k) {
    const double lo = out.s_min + k * partition_length;
    const double hi = std::min(out.s_max, lo + partition_length);
    out.centers.push_back(count == 1 ? 0.5 * (out.s_min + out.s_max) : 0.5 * (lo + hi));
  }
  out.index_of.resize(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) {
    const int k = static_cast<int>(std::floor((s[i] - out.s_min) / partition_length));
    out.index_of[i] = std::clamp(k, 0, count - 1);
  }
  const double s_query = out.axis.dot(query - out.origin);
  std::vector<int> order(count);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return std::abs(out.centers[a] - s_query) < std::abs(out.centers[b] - s_query);
  });
  for (int k : order) {
    if (out.selected.size() == 2 || std::abs(out.centers[k] - s_query) >= partition_length) break;
    out.selected.push_back(k);
  }
  if (out.selected.empty()) out.selected.push_back(order.front());
  return out;
}

}  // namespace tacs
