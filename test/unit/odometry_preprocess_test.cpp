#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "tacs_graphs/odometry/preprocess.h"

namespace tacs {
namespace {

pcl::PointXYZI point(float x, float y, float z, float intensity = 0.0f) {
  pcl::PointXYZI p;
  p.x = x;
  p.y = y;
  p.z = z;
  p.intensity = intensity;
  return p;
}

TEST(Preprocess, DropsNonFiniteZeroAndOutOfRangePoints) {
  PointCloud in;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  in.push_back(point(nan, 1, 1));
  in.push_back(point(1, inf, 1));
  in.push_back(point(1, 1, -inf));
  in.push_back(point(0, 0, 0));    // "no return"
  in.push_back(point(0.1, 0, 0));  // closer than min_range
  in.push_back(point(50, 0, 0));   // beyond max_range
  in.push_back(point(3, 0, 0));    // kept
  in.push_back(point(0, -7, 1));   // kept
  PreprocessConfig config;
  config.voxel_size_m = 0.0;
  PreprocessStats stats;
  const PointCloud out = preprocess(in, config, &stats);
  EXPECT_EQ(stats.input, 8u);
  EXPECT_EQ(stats.non_finite, 3u);
  EXPECT_EQ(stats.out_of_range, 3u);
  EXPECT_EQ(stats.output, 2u);
  ASSERT_EQ(out.size(), 2u);
  for (const auto& p : out.points) {
    const double r = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    EXPECT_GE(r, config.min_range_m);
    EXPECT_LE(r, config.max_range_m);
  }
}

TEST(Preprocess, ZeroPointsAreDroppedEvenWithoutMinimumRange) {
  PointCloud in;
  in.push_back(point(0, 0, 0));
  in.push_back(point(1, 0, 0));
  PreprocessConfig config;
  config.min_range_m = 0.0;
  PreprocessStats stats;
  EXPECT_EQ(preprocess(in, config, &stats).size(), 1u);
  EXPECT_EQ(stats.out_of_range, 1u);
}

TEST(Preprocess, EmptyAndAllNanInputsGiveEmptyOutput) {
  PreprocessStats stats;
  EXPECT_TRUE(preprocess(PointCloud(), PreprocessConfig(), &stats).empty());
  EXPECT_EQ(stats.input, 0u);
  PointCloud nans;
  for (int i = 0; i < 100; ++i) nans.push_back(point(NAN, NAN, NAN));
  EXPECT_TRUE(preprocess(nans, PreprocessConfig(), &stats).empty());
  EXPECT_EQ(stats.non_finite, 100u);
  EXPECT_EQ(stats.output, 0u);
}

// Point times follow the points: dropped with them, averaged per voxel like the coordinates.
TEST(Preprocess, CarriesThePointTimesThroughCropAndVoxelGrid) {
  PointCloud in;
  in.push_back(point(3.01f, 0.01f, 0.01f));
  in.push_back(point(0.0f, 0.0f, 0.0f));  // "no return": dropped with its time
  in.push_back(point(3.03f, 0.03f, 0.03f));
  in.push_back(point(0.01f, 5.01f, 0.01f));
  const std::vector<float> times = {0.010f, 0.5f, 0.012f, 0.07f};
  std::vector<float> out_times;
  const PointCloud out = preprocess(in, PreprocessConfig(), nullptr, &times, &out_times);
  ASSERT_EQ(out.size(), 2u);
  ASSERT_EQ(out_times.size(), 2u);
  EXPECT_NEAR(out_times[0], 0.011f, 1e-6);
  EXPECT_NEAR(out_times[1], 0.07f, 1e-6);
  // Times of another length are ignored: no times out.
  const std::vector<float> short_times = {0.01f};
  preprocess(in, PreprocessConfig(), nullptr, &short_times, &out_times);
  EXPECT_TRUE(out_times.empty());
}

TEST(VoxelDownsample, KeepsReturnsFarApartInTimeInSeparateCentroids) {
  // A sweep's seam: its first and last firings hit the same voxel from poses the motion has
  // moved apart, so their centroid could not be deskewed with one time.
  PointCloud in;
  in.push_back(point(2.01f, 0.01f, 0.01f));
  in.push_back(point(2.02f, 0.02f, 0.02f));
  in.push_back(point(2.03f, 0.03f, 0.03f));
  in.push_back(point(9.0f, 9.0f, 0.0f));
  const std::vector<float> times = {-0.050f, -0.049f, 0.049f, 0.0f};
  std::vector<float> out_times;
  const PointCloud out = voxelDownsample(in, 0.2, &times, &out_times);
  ASSERT_EQ(out.size(), 3u);
  ASSERT_EQ(out_times.size(), 3u);
  EXPECT_NEAR(out_times[0], -0.0495f, 1e-6);
  EXPECT_NEAR(out.points[0].x, 2.015f, 1e-5);
  EXPECT_NEAR(out_times[1], 0.049f, 1e-6);
  EXPECT_NEAR(out.points[1].x, 2.03f, 1e-5);
  // Without times the same voxel is one centroid.
  EXPECT_EQ(voxelDownsample(in, 0.2).size(), 2u);
}

TEST(VoxelDownsample, AveragesPointsOfOneVoxelAndKeepsOthersApart) {
  PointCloud in;
  for (int i = 0; i < 10; ++i) in.push_back(point(1.01f + 0.01f * i, 2.05f, 3.05f, i));
  in.push_back(point(5.05f, 2.05f, 3.05f, 7));
  const PointCloud out = voxelDownsample(in, 0.2);
  ASSERT_EQ(out.size(), 2u);
  const auto& a = out.points[0].x < 3 ? out.points[0] : out.points[1];
  EXPECT_NEAR(a.x, 1.055, 1e-4);
  EXPECT_NEAR(a.y, 2.05, 1e-4);
  EXPECT_NEAR(a.intensity, 4.5, 1e-4);
}

TEST(VoxelDownsample, HandlesLargeExtentsWithoutMergingDistantPoints) {
  // 2e5 m across at 5 cm voxels: 4e6 voxels per axis would overflow a 32-bit index grid.
  PointCloud in;
  in.push_back(point(-1e5f, 0, 0));
  in.push_back(point(1e5f, 0, 0));
  in.push_back(point(0, 1e5f, -1e5f));
  in.push_back(point(0, 1e5f, -1e5f));
  const PointCloud out = voxelDownsample(in, 0.05);
  EXPECT_EQ(out.size(), 3u);
}

TEST(VoxelDownsample, NearAndFarVoxelsKeepTheOrderOfTheirFirstPoint) {
  // Near voxels are hashed as packed 64-bit keys, voxels beyond +-2^19 edges as full keys: both
  // number one sequence of centroids.
  PointCloud in;
  in.push_back(point(1.01f, 0.01f, 0.01f, 1));
  in.push_back(point(3e4f, 0.01f, 0.01f, 2));  // 600k voxels of 5 cm out
  in.push_back(point(1.02f, 0.02f, 0.02f, 3));
  in.push_back(point(-2.01f, 0.01f, 0.01f, 4));
  in.push_back(point(3e4f, 0.02f, 0.02f, 6));
  const PointCloud out = voxelDownsample(in, 0.05);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_NEAR(out.points[0].x, 1.015f, 1e-5);
  EXPECT_NEAR(out.points[0].intensity, 2.0f, 1e-5);
  EXPECT_NEAR(out.points[1].x, 3e4f, 1e-2);
  EXPECT_NEAR(out.points[1].intensity, 4.0f, 1e-5);
  EXPECT_NEAR(out.points[2].x, -2.01f, 1e-5);
}

}  // namespace
}  // namespace tacs
