// Room partitions of CoSG-LCD (paper Sec. III-D, Fig. 5(a)).
#include <gtest/gtest.h>

#include <cmath>

#include "tacs_graphs/loop_closure/room_partitions.h"

namespace tacs {
namespace {

// Positions every metre along a 30 m line at 30 deg: the room's long axis.
std::vector<Eigen::Vector2d> diagonalRoom(Eigen::Vector2d* dir) {
  *dir = Eigen::Vector2d(std::cos(M_PI / 6), std::sin(M_PI / 6));
  std::vector<Eigen::Vector2d> positions;
  for (int i = 0; i <= 30; ++i) {
    // a little sideways spread, as a path through a hall has
    positions.push_back(Eigen::Vector2d(5, -2) + i * *dir +
                        (i % 2 ? 0.8 : -0.8) * Eigen::Vector2d(-dir->y(), dir->x()));
  }
  return positions;
}

TEST(LoopClosurePartitions, SplitsALargeRoomAlongItsLongAxis) {
  Eigen::Vector2d dir;
  const auto positions = diagonalRoom(&dir);
  const RoomPartitions p = partitionRoom(positions, positions[13], 8.0);
  EXPECT_NEAR(std::abs(p.axis.dot(dir)), 1.0, 1e-3);
  EXPECT_NEAR(p.s_max - p.s_min, 30.0, 0.05);
  ASSERT_EQ(p.centers.size(), 4u);  // 8 + 8 + 8 + 6 m
  // Partition index grows along the axis, 8 positions per full partition.
  for (size_t i = 1; i < positions.size(); ++i) EXPECT_GE(p.index_of[i], p.index_of[i - 1]);
  EXPECT_EQ(p.index_of[0], 0);
  EXPECT_EQ(p.index_of[7], 0);
  EXPECT_EQ(p.index_of[9], 1);
  EXPECT_EQ(p.index_of[30], 3);
  // Query at 13 m: centres 4, 12, 20, 27 -> 12 (1 m) and 20 (7 m) are closer than L_part.
  EXPECT_EQ(p.selected, (std::vector<int>{1, 2}));
}

TEST(LoopClosurePartitions, SelectsOnlyPartitionsCloserThanLPart) {
  Eigen::Vector2d dir;
  const auto positions = diagonalRoom(&dir);
  // At 29 m: centres 27 (2 m) and 20 (9 m, not < L_part).
  EXPECT_EQ(partitionRoom(positions, positions[29], 8.0).selected, (std::vector<int>{3}));
  // Far beyond the room, the nearest partition is still searched.
  const Eigen::Vector2d beyond = positions[30] + 20.0 * dir;
  EXPECT_EQ(partitionRoom(positions, beyond, 8.0).selected, (std::vector<int>{3}));
}

TEST(LoopClosurePartitions, ASmallRoomIsOnePartition) {
  const std::vector<Eigen::Vector2d> positions = {{0, 0}, {2, 1}, {4, 0.5}, {1, 2}};
  const RoomPartitions p = partitionRoom(positions, {2, 1}, 8.0);
  ASSERT_EQ(p.centers.size(), 1u);
  EXPECT_EQ(p.selected, (std::vector<int>{0}));
  for (int k : p.index_of) EXPECT_EQ(k, 0);
  EXPECT_EQ(partitionRoom({{3, 3}}, {0, 0}, 8.0).selected, (std::vector<int>{0}));
  EXPECT_TRUE(partitionRoom({}, {0, 0}, 8.0).selected.empty());
}

}  // namespace
}  // namespace tacs
