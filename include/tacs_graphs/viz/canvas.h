// A small raster canvas for top-down figures (worlds, maps, scene graphs): world metres are
// mapped to pixels at a fixed resolution, x right and y up. Colours blend by their alpha.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace tacs::viz {

struct Rgba {
  uint8_t r = 0, g = 0, b = 0, a = 255;
};

class Canvas {
 public:
  /// Covers [min_xy, max_xy] (metres) at `resolution_m` metres per pixel.
  Canvas(const Eigen::Vector2d& min_xy, const Eigen::Vector2d& max_xy, double resolution_m,
         Rgba background = {255, 255, 255, 255});

  int width() const { return width_; }
  int height() const { return height_; }
  /// Continuous pixel coordinates (column, row) of a world point.
  Eigen::Vector2d toPixel(const Eigen::Vector2d& world) const;
  Rgba pixel(int col, int row) const;

  void drawLine(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Rgba color,
                double thickness_px = 1.0);
  void drawPolyline(const std::vector<Eigen::Vector2d>& points, Rgba color,
                    double thickness_px = 1.0, bool closed = false);
  /// Even-odd fill; color.a is the opacity.
  void fillPolygon(const std::vector<Eigen::Vector2d>& points, Rgba color);
  void drawCircle(const Eigen::Vector2d& center, double radius_m, Rgba color,
                  double thickness_px = 1.0);
  void fillCircle(const Eigen::Vector2d& center, double radius_m, Rgba color);
  /// Text in a built-in 5x7 font (digits, letters, a little punctuation; lower case is drawn
  /// as upper case), its top-left corner at a world point; `scale` multiplies the glyph size.
  void drawText(const Eigen::Vector2d& top_left, const std::string& text, Rgba color,
                int scale = 1);
  void drawTextPx(int col, int row, const std::string& text, Rgba color, int scale = 1);

  /// Writes an 8-bit RGBA PNG. Throws std::runtime_error naming the path on failure.
  void savePng(const std::string& path) const;

 private:
  void blend(int col, int row, Rgba color);
  /// Blends every pixel whose centre passes `inside(x, y)` within the pixel box [x0,x1]x[y0,y1].
  template <class Inside>
  void fillWhere(double x0, double y0, double x1, double y1, Rgba color, Inside inside);

  Eigen::Vector2d min_;
  double resolution_;
  int width_, height_;
  std::vector<uint8_t> rgba_;
};

}  // namespace tacs::viz
