#include "tacs_graphs/odometry/preprocess.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "tacs_graphs/common/config.h"
#include "tacs_graphs/odometry/voxel_index.h"

namespace tacs {

void PreprocessConfig::validate() const {
  requireConfig(min_range_m >= 0.0, "odometry.preprocess.min_range_m", "must be >= 0");
  requireConfig(max_range_m > min_range_m, "odometry.preprocess.max_range_m",
                "must be > min_range_m");
  requireConfig(voxel_size_m >= 0.0 && std::isfinite(voxel_size_m),
                "odometry.preprocess.voxel_size_m", "must be >= 0 (0 disables downsampling)");
  requireConfig(max_points >= 0, "odometry.preprocess.max_points", "must be >= 0 (0: no budget)");
}

namespace {

bool isFinitePoint(const pcl::PointXYZI& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

// Integer voxel coordinates (and a time slot) to a running centroid, emitted in order of each
// voxel's first point.
class VoxelTable {
 public:
  explicit VoxelTable(size_t expected) : index_(expected) { cells_.reserve(expected); }

  void add(const VoxelIndex::Key& key, const pcl::PointXYZI& p, float time) {
    const size_t i = index_.insert(key);
    if (i == cells_.size()) cells_.push_back({Eigen::Vector4d::Zero(), 0.0, 0});
    Cell& c = cells_[i];
    c.sum += Eigen::Vector4d(p.x, p.y, p.z, p.intensity);
    c.time_sum += time;
    ++c.count;
  }

  // The centroids, and the mean point time of each when `times` is given.
  void appendCentroids(PointCloud* out, std::vector<float>* times) const {
    out->points.reserve(out->points.size() + cells_.size());
    for (const Cell& c : cells_) {
      if (times) times->push_back(static_cast<float>(c.time_sum / static_cast<double>(c.count)));
      const Eigen::Vector4d mean = c.sum / static_cast<double>(c.count);
      pcl::PointXYZI q;
      q.x = static_cast<float>(mean[0]);
      q.y = static_cast<float>(mean[1]);
      q.z = static_cast<float>(mean[2]);
      q.intensity = static_cast<float>(mean[3]);
      out->points.push_back(q);
    }
  }

 private:
  struct Cell {
    Eigen::Vector4d sum;
    double time_sum;
    int64_t count;
  };
  VoxelIndex index_;
  std::vector<Cell> cells_;
};

// Points whose times lie more than an eighth of the sweep apart never share a voxel: the sweep's
// first and last firings meet at its seam, where the motion has moved them apart, and a centroid
// of both could not be deskewed by one time. Neighbouring returns of one firing keep one slot.
constexpr double kTimeSlotsPerSweep = 8.0;

}  // namespace

PointCloud voxelDownsample(const PointCloud& in, double voxel_size, const std::vector<float>* times,
                           std::vector<float>* times_out) {
  PointCloud out;
  out.header = in.header;
  const bool timed = times && times_out && times->size() == in.points.size();
  if (times_out) times_out->clear();
  if (voxel_size > 0.0) {
    const double inv = 1.0 / voxel_size;
    double t_lo = 0.0, slot_inv = 0.0;
    if (timed && !times->empty()) {
      const auto [lo, hi] = std::minmax_element(times->begin(), times->end());
      t_lo = *lo;
      if (*hi > *lo) slot_inv = kTimeSlotsPerSweep / (double(*hi) - double(*lo));
    }
    VoxelTable table(in.points.size() / 4);  // grows when more voxels are occupied
    for (size_t i = 0; i < in.points.size(); ++i) {
      const auto& p = in.points[i];
      if (!isFinitePoint(p)) continue;
      const Eigen::Vector3d scaled = Eigen::Vector3d(p.x, p.y, p.z) * inv;
      if (scaled.cwiseAbs().maxCoeff() > 1e18) continue;  // would overflow a 64-bit index
      const float time = timed ? (*times)[i] : 0.0f;
      table.add(
          {static_cast<int64_t>(std::floor(scaled.x())),
           static_cast<int64_t>(std::floor(scaled.y())),
           static_cast<int64_t>(std::floor(scaled.z())),
           std::isfinite(time) ? static_cast<int64_t>(std::floor((time - t_lo) * slot_inv)) : 0},
          p, time);
    }
    table.appendCentroids(&out, timed ? times_out : nullptr);
  } else {
    for (size_t i = 0; i < in.points.size(); ++i) {
      if (!isFinitePoint(in.points[i])) continue;
      out.points.push_back(in.points[i]);
      if (timed) times_out->push_back((*times)[i]);
    }
  }
  out.width = static_cast<uint32_t>(out.points.size());
  out.height = 1;
  out.is_dense = true;
  return out;
}

PointCloud preprocess(const PointCloud& in, const PreprocessConfig& config, PreprocessStats* stats,
                      const std::vector<float>* times, std::vector<float>* times_out) {
  const bool timed = times && times_out && times->size() == in.points.size();
  if (times_out) times_out->clear();
  std::vector<float> kept_times;
  PreprocessStats s;
  s.input = in.points.size();
  PointCloud kept;
  kept.header = in.header;
  kept.points.reserve(in.points.size());
  const double min_sq = config.min_range_m * config.min_range_m;
  const double max_sq = config.max_range_m * config.max_range_m;
  for (size_t i = 0; i < in.points.size(); ++i) {
    const auto& p = in.points[i];
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
    if (timed) kept_times.push_back((*times)[i]);
  }
  kept.width = static_cast<uint32_t>(kept.points.size());
  kept.height = 1;
  std::vector<float>* out_times = timed ? times_out : nullptr;
  PointCloud out = voxelDownsample(kept, config.voxel_size_m, &kept_times, out_times);
  s.voxel_size_m = config.voxel_size_m;
  // Point budget: on surfaces the count falls with the voxel edge squared, so a dense LiDAR's
  // scan is regridded coarser (from the first grid's centroids, which is cheap) until it fits.
  const size_t budget = static_cast<size_t>(std::max(0, config.max_points));
  for (int pass = 0; budget > 0 && s.voxel_size_m > 0.0 && out.size() > budget && pass < 4;
       ++pass) {
    s.voxel_size_m *= 1.05 * std::sqrt(static_cast<double>(out.size()) / budget);
    const std::vector<float> pass_times = out_times ? *out_times : std::vector<float>();
    out = voxelDownsample(out, s.voxel_size_m, &pass_times, out_times);
  }
  s.output = out.points.size();
  if (stats) *stats = s;
  return out;
}

}  // namespace tacs
