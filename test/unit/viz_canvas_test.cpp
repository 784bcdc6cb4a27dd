#include <gtest/gtest.h>

#include <filesystem>

#include "tacs_graphs/viz/canvas.h"

namespace tacs::viz {
namespace {

TEST(VizCanvas, MapsMetresToPixelsAndDraws) {
  Canvas c(Eigen::Vector2d(-1, -1), Eigen::Vector2d(3, 1), 0.1);
  EXPECT_EQ(c.width(), 40);
  EXPECT_EQ(c.height(), 20);
  EXPECT_TRUE(c.toPixel(Eigen::Vector2d(-1, 1)).isApprox(Eigen::Vector2d(0, 0)));
  EXPECT_TRUE(c.toPixel(Eigen::Vector2d(0, 0)).isApprox(Eigen::Vector2d(10, 10)));
  // Half-transparent red square over white: pink inside, white outside.
  c.fillPolygon({{0, 0}, {1, 0}, {1, 0.5}, {0, 0.5}}, {255, 0, 0, 128});
  const Rgba in = c.pixel(15, 7), out = c.pixel(25, 7);
  EXPECT_EQ(in.r, 255);
  EXPECT_NEAR(in.g, 127, 1);
  EXPECT_EQ(out.g, 255);
  // A 3 px black line along y = -0.5 (row 15): pixel centres within 1.5 px of it are covered.
  c.drawLine({-0.5, -0.5}, {2.5, -0.5}, {0, 0, 0, 255}, 3.0);
  EXPECT_EQ(c.pixel(20, 15).r, 0);
  EXPECT_EQ(c.pixel(20, 12).r, 255);
  c.fillCircle({2, 0.5}, 0.2, {0, 0, 255, 255});
  EXPECT_EQ(c.pixel(30, 5).b, 255);
  EXPECT_EQ(c.pixel(30, 5).r, 0);
  // Text: "1" has a vertical stroke in its middle column.
  Canvas t(Eigen::Vector2d(0, 0), Eigen::Vector2d(2, 1), 0.1);
  t.drawTextPx(2, 2, "1", {0, 0, 0, 255});
  EXPECT_EQ(t.pixel(4, 5).r, 0);
  EXPECT_EQ(t.pixel(2, 5).r, 255);
  const std::string path = ::testing::TempDir() + "/canvas_test.png";
  c.savePng(path);
  EXPECT_GT(std::filesystem::file_size(path), 50u);
  EXPECT_THROW(c.savePng("/nonexistent/dir/x.png"), std::runtime_error);
}

}  // namespace
}  // namespace tacs::viz
