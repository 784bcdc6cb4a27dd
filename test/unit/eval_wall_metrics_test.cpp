// Wall precision against ground truth (eval/wall_metrics.h).
#include <gtest/gtest.h>

#include "tacs_graphs/eval/wall_metrics.h"

namespace tacs {
namespace {

WallNode wallNode(Eigen::Vector2d a, Eigen::Vector2d b, bool is_wall = true) {
  WallNode w;
  const Eigen::Vector2d u = (b - a).normalized();
  w.normal = Eigen::Vector3d(-u.y(), u.x(), 0.0);
  w.d = -w.normal.head<2>().dot(a);
  w.endpoints = {a, b};
  w.is_wall = is_wall;
  return w;
}

sim::Wall groundTruthWall(Eigen::Vector2d from, Eigen::Vector2d to) {
  sim::Wall w;
  w.from = from;
  w.to = to;
  w.thickness = 0.2;
  return w;
}

TEST(EvaluateWalls, AWallOnEitherFaceOfAWorldWallIsCorrectOneOnFurnitureIsNot) {
  const std::vector<sim::Wall> truth = {groundTruthWall({0, 0}, {10, 0})};
  SceneGraph graph;
  graph.walls[0] = wallNode({1, 0.1}, {9, 0.1});         // the north face
  graph.walls[1] = wallNode({2, -0.12}, {6, -0.08});     // the south face, slightly tilted
  graph.walls[2] = wallNode({2, 3.0}, {8, 3.0});         // a rack face 3 m away
  graph.walls[3] = wallNode({0.1, 0.1}, {0.1, 4.0});     // across the wall's end
  graph.walls[4] = wallNode({2, 3.0}, {8, 3.0}, false);  // no wall: not scored
  const WallMetrics m = evaluateWalls(graph, truth);
  EXPECT_EQ(m.walls, 4u);
  EXPECT_EQ(m.correct, 2u);
  EXPECT_DOUBLE_EQ(m.precision(), 0.5);
}

TEST(EvaluateWalls, AWallMostlyPastTheWorldWallsEndIsNotOnIt) {
  const std::vector<sim::Wall> truth = {groundTruthWall({0, 0}, {4, 0})};
  SceneGraph graph;
  graph.walls[0] = wallNode({3, 0.1}, {9, 0.1});  // 1.1 m of 6 m over the wall
  EXPECT_EQ(evaluateWalls(graph, truth).correct, 0u);
  EXPECT_DOUBLE_EQ(evaluateWalls(SceneGraph(), truth).precision(), 1.0);
}

}  // namespace
}  // namespace tacs
