// Scan preprocessing for odometry: drop invalid returns, crop by range, voxel downsample.
#pragma once

#include <cstddef>
#include <vector>

#include "tacs_graphs/common/types.h"

namespace tacs {

struct PreprocessConfig {
  double min_range_m = 0.5;   // [m] closer returns hit the robot itself
  double max_range_m = 40.0;  // [m] farther returns are sparse and noisy indoors
  double voxel_size_m = 0.2;  // [m] voxel edge of the downsampling grid; 0 disables downsampling
  // Point budget per scan: a denser result is regridded with a coarser voxel until it fits, so
  // a 128-beam scan costs about what a 16-beam one does (0: no budget).
  int max_points = 0;

  template <class V>
  void visit(V& v) {
    v("min_range_m", min_range_m);
    v("max_range_m", max_range_m);
    v("voxel_size_m", voxel_size_m);
    v("max_points", max_points);
  }
  void validate() const;
};

/// What preprocess() did with the points: input = non_finite + out_of_range + kept, and `output`
/// is the number of voxel centroids made from the kept points.
struct PreprocessStats {
  size_t input = 0, non_finite = 0, out_of_range = 0, output = 0;
  double voxel_size_m = 0.0;  // [m] the voxel edge used (larger than configured under a budget)
};

/// Removes non-finite points and points whose distance to the origin is outside
/// [min_range_m, max_range_m] (this also drops the exact (0,0,0) "no return" points), then
/// replaces the points of each voxel by their centroid (intensity averaged). Never throws on bad
/// data; an all-invalid input gives an empty cloud. With `times` (one per input point) and
/// `times_out`, the mean time of each output point's inputs goes to `times_out`.
PointCloud preprocess(const PointCloud& in, const PreprocessConfig& config,
                      PreprocessStats* stats = nullptr, const std::vector<float>* times = nullptr,
                      std::vector<float>* times_out = nullptr);

/// Voxel-grid downsampling by hashing integer voxel coordinates (no dense grid, so any extent
/// works, unlike a fixed-size index grid). Each occupied voxel yields the centroid of its points.
/// Non-finite points are skipped. Voxels come out in the order of their first point
/// (deterministic). voxel_size <= 0 copies the finite points. With `times` (one per input point)
/// and `times_out`, each output point's mean input time goes to `times_out`, and points more than
/// an eighth of the times' span apart are kept in separate voxels (a sweep's seam).
PointCloud voxelDownsample(const PointCloud& in, double voxel_size,
                           const std::vector<float>* times = nullptr,
                           std::vector<float>* times_out = nullptr);

}  // namespace tacs
