#include "tacs_graphs/odometry/preprocess.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "tacs_graphs/common/config.h"

namespace tacs {

void PreprocessConfig::validate() const {
  requireConfig(min_range_m >= 0.0, "preprocess.min_range_m", "must be >= 0");
  requireConfig(max_range_m > min_range_m, "preprocess.max_range_m", "must be > min_range_m");
  requireConfig(voxel_size_m >= 0.0 && std::isfinite(voxel_size_m), "preprocess.voxel_size_m",
                "must be >= 0 (0 disables downsampling)");
}

namespace {

bool isFinitePoint(const pcl::PointXYZI& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

// Sorts (voxel key, point index) pairs so each voxel's points form one run, and appends the
// centroid of each run. Sorting instead of a hash map keeps the output order deterministic.
template <class Key>
void appendVoxelCentroids(const PointCloud& in, std::vector<std::pair<Key, uint32_t>>* keyed,
                          PointCloud* out) {
  std::sort(keyed->begin(), keyed->end());
  for (size_t begin = 0; begin < keyed->size();) {
    size_t end = begin;
    Eigen::Vector4d sum = Eigen::Vector4d::Zero();
    for (; end < keyed->size() && (*keyed)[end].first == (*keyed)[begin].first; ++end) {
      const auto& p = in.points[(*keyed)[end].second];
      sum += Eigen::Vector4d(p.x, p.y, p.z, p.intensity);
    }
    sum /= static_cast<double>(end - begin);
    pcl::PointXYZI c;
    c.x = static_cast<float>(sum[0]);
    c.y = static_cast<float>(sum[1]);
    c.z = static_cast<float>(sum[2]);
    c.intensity = static_cast<float>(sum[3]);
    out->points.push_back(c);
    begin = end;
  }
}

// Voxel coordinates relative to the minimum corner pack into one 64-bit key (21 bits per axis)
// when the extent allows, which covers 400 km at 0.2 m; wider clouds use a 3-integer key.
constexpr int kAxisBits = 21;
constexpr int64_t kAxisMax = (int64_t{1} << kAxisBits) - 1;

}  // namespace

PointCloud voxelDownsample(const PointCloud& in, double voxel_size) {
  PointCloud out;
  out.header = in.header;
  std::vector<std::array<int64_t, 3>> cells;
  std::vector<uint32_t> indices;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
  for (const auto& p : in.points) {
    if (isFinitePoint(p)) lo = lo.cwiseMin(Eigen::Vector3d(p.x, p.y, p.z));
  }
  const double inv = voxel_size > 0.0 ? 1.0 / voxel_size : 0.0;
  int64_t extent = 0;
  for (size_t i = 0; i < in.points.size(); ++i) {
    const auto& p = in.points[i];
    if (!isFinitePoint(p)) continue;
    if (!(voxel_size > 0.0)) {
      out.points.push_back(p);
      continue;
    }
    const Eigen::Vector3d scaled = (Eigen::Vector3d(p.x, p.y, p.z) - lo) * inv;
    if (scaled.maxCoeff() > 1e18) continue;  // would overflow a 64-bit voxel index
    const std::array<int64_t, 3> cell = {static_cast<int64_t>(scaled.x()),
                                         static_cast<int64_t>(scaled.y()),
                                         static_cast<int64_t>(scaled.z())};
    extent = std::max({extent, cell[0], cell[1], cell[2]});
    cells.push_back(cell);
    indices.push_back(static_cast<uint32_t>(i));
  }
  if (extent <= kAxisMax) {
    std::vector<std::pair<uint64_t, uint32_t>> keyed(cells.size());
    for (size_t k = 0; k < cells.size(); ++k) {
      keyed[k] = {static_cast<uint64_t>(cells[k][0]) << (2 * kAxisBits) |
                      static_cast<uint64_t>(cells[k][1]) << kAxisBits |
                      static_cast<uint64_t>(cells[k][2]),
                  indices[k]};
    }
    appendVoxelCentroids(in, &keyed, &out);
  } else {
    std::vector<std::pair<std::array<int64_t, 3>, uint32_t>> keyed(cells.size());
    for (size_t k = 0; k < cells.size(); ++k) keyed[k] = {cells[k], indices[k]};
    appendVoxelCentroids(in, &keyed, &out);
  }
  out.width = static_cast<uint32_t>(out.points.size());
  out.height = 1;
  out.is_dense = true;
  return out;
}

PointCloud preprocess(const PointCloud& in, const PreprocessConfig& config,
                      PreprocessStats* stats) {
  PreprocessStats s;
  s.input = in.points.size();
  PointCloud kept;
  kept.header = in.header;
  kept.points.reserve(in.points.size());
  const double min_sq = config.min_range_m * config.min_range_m;
  const double max_sq = config.max_range_m * config.max_range_m;
  for (const auto& p : in.points) {
    if (!isFinitePoint(p)) {
      ++s.non_finite;
      continue;
    }
    const double r_sq = double(p.x) * p.x + double(p.y) * p.y + double(p.z) * p.z;
    // r == 0 is the "no return" marker of many drivers: dropped even with min_range_m = 0.
    if (r_sq < min_sq || r_sq > max_sq || r_sq == 0.0) {
      ++s.out_of_range;
      continue;
    }
    kept.points.push_back(p);
  }
  kept.width = static_cast<uint32_t>(kept.points.size());
  kept.height = 1;
  PointCloud out = voxelDownsample(kept, config.voxel_size_m);
  s.output = out.points.size();
  if (stats) *stats = s;
  return out;
}

}  // namespace tacs
