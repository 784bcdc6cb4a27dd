#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "tacs_graphs/odometry/kd_tree.h"

namespace tacs {
namespace {

float bruteDistance(const Eigen::Vector3d& p, const Eigen::Vector3f& q) {
  const Eigen::Vector3f f = p.cast<float>();
  const float dx = q.x() - f.x(), dy = q.y() - f.y(), dz = q.z() - f.z();
  return dx * dx + dy * dy + dz * dz;
}

// A LiDAR-like cloud: dense patches on a few planes, sparse points between them, exact
// duplicates and a collinear run (degenerate cells).
std::vector<Eigen::Vector3d> awkwardCloud(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 1500; ++i) points.emplace_back(5.0 + 0.01 * u(rng), 3.0 * u(rng), u(rng));
  for (int i = 0; i < 1500; ++i) points.emplace_back(8.0 * u(rng), 8.0 * u(rng), -1.0);
  for (int i = 0; i < 200; ++i) points.emplace_back(20.0 * u(rng), 20.0 * u(rng), 5.0 * u(rng));
  for (int i = 0; i < 40; ++i) points.emplace_back(1.0, 2.0, 3.0);
  for (int i = 0; i < 60; ++i) points.emplace_back(0.05 * i, -7.0, 0.5);
  return points;
}

TEST(KdTree3, NearestIsTheExactNearestBelowTheBound) {
  std::mt19937 rng(3);
  const std::vector<Eigen::Vector3d> points = awkwardCloud(rng);
  const KdTree3 tree(points);
  ASSERT_EQ(tree.size(), points.size());
  std::uniform_real_distribution<float> u(-25.0f, 25.0f);
  for (int trial = 0; trial < 2000; ++trial) {
    // Queries inside and far outside the cloud, with tight and loose bounds.
    const Eigen::Vector3f q(u(rng), u(rng), 0.3f * u(rng));
    const float bound = trial % 3 == 0 ? 1e30f : trial % 3 == 1 ? 4.0f : 0.25f;
    float best = bound;
    for (const Eigen::Vector3d& p : points) best = std::min(best, bruteDistance(p, q));
    float dist = -1.0f;
    const int64_t j = tree.nearest(q, bound, &dist);
    if (best < bound) {
      ASSERT_GE(j, 0) << "trial " << trial;
      EXPECT_EQ(dist, best);
      EXPECT_EQ(bruteDistance(points[j], q), best);
    } else {
      EXPECT_EQ(j, -1);
      EXPECT_EQ(dist, bound);
    }
  }
}

TEST(KdTree3, KnnReturnsTheKClosestSortedAndStoresThePoints) {
  std::mt19937 rng(5);
  const std::vector<Eigen::Vector3d> points = awkwardCloud(rng);
  const KdTree3 tree(points);
  std::uniform_real_distribution<float> u(-10.0f, 10.0f);
  for (int trial = 0; trial < 500; ++trial) {
    const Eigen::Vector3f q(u(rng), u(rng), 0.2f * u(rng));
    const size_t k = 1 + trial % 25;
    std::vector<float> all;
    for (const Eigen::Vector3d& p : points) all.push_back(bruteDistance(p, q));
    std::sort(all.begin(), all.end());
    std::vector<uint32_t> ids(k);
    std::vector<float> dist(k);
    ASSERT_EQ(tree.knn(q, k, ids.data(), dist.data()), k);
    for (size_t i = 0; i < k; ++i) {
      EXPECT_EQ(dist[i], all[i]) << "trial " << trial << " rank " << i;
      EXPECT_EQ(bruteDistance(points[ids[i]], q), dist[i]);
    }
  }
  for (uint32_t i = 0; i < points.size(); i += 97) {
    EXPECT_EQ(tree.point(i), points[i].cast<float>());
  }
}

TEST(KdTree3, SmallAndEmptyClouds) {
  const KdTree3 empty(std::vector<Eigen::Vector3d>{});
  float dist = 0.0f;
  EXPECT_EQ(empty.nearest(Eigen::Vector3f::Zero(), 1.0f, &dist), -1);
  uint32_t id = 0;
  EXPECT_EQ(empty.knn(Eigen::Vector3f::Zero(), 3, &id, &dist), 0u);

  const KdTree3 two({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0)});
  std::vector<uint32_t> ids(5);
  std::vector<float> dists(5);
  ASSERT_EQ(two.knn(Eigen::Vector3f(0.9f, 0, 0), 5, ids.data(), dists.data()), 2u);
  EXPECT_EQ(ids[0], 1u);
  EXPECT_EQ(ids[1], 0u);
  // 50 copies of one point: one leaf, any of them is the nearest.
  const KdTree3 same(std::vector<Eigen::Vector3d>(50, Eigen::Vector3d(2, 2, 2)));
  EXPECT_GE(same.nearest(Eigen::Vector3f(2, 2, 2.5f), 1.0f, &dist), 0);
  EXPECT_FLOAT_EQ(dist, 0.25f);
}

}  // namespace
}  // namespace tacs
