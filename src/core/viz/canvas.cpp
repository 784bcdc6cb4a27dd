#include "tacs_graphs/viz/canvas.h"

#include <png.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "tacs_graphs/common/types.h"

namespace tacs::viz {
namespace {

// 5x7 glyphs, one byte per row (bit 4 = leftmost column).
constexpr char kGlyphChars[] = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ-.:_/()=%+,";
constexpr uint8_t kGlyphs[][7] = {
    {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}, {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E},
    {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}, {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E},
    {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}, {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E},
    {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}, {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08},
    {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}, {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C},
    {0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}, {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E},
    {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}, {0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C},
    {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}, {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10},
    {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F}, {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11},
    {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}, {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C},
    {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}, {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F},
    {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}, {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11},
    {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}, {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10},
    {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D}, {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11},
    {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}, {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04},
    {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}, {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04},
    {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A}, {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11},
    {0x11, 0x11, 0x0A, 0x04, 0x04, 0x04, 0x04}, {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F},
    {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}, {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C},
    {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}, {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1F},
    {0x01, 0x01, 0x02, 0x04, 0x08, 0x10, 0x10}, {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02},
    {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}, {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00},
    {0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03}, {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00},
    {0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08},
};
static_assert(sizeof(kGlyphs) / sizeof(kGlyphs[0]) == sizeof(kGlyphChars) - 1);

}  // namespace

Canvas::Canvas(const Eigen::Vector2d& min_xy, const Eigen::Vector2d& max_xy, double resolution_m,
               Rgba background)
    : min_(min_xy), resolution_(resolution_m) {
  if (!(resolution_m > 0)) throw std::invalid_argument("Canvas: resolution must be > 0");
  width_ = std::max(1, static_cast<int>(std::ceil((max_xy.x() - min_xy.x()) / resolution_m)));
  height_ = std::max(1, static_cast<int>(std::ceil((max_xy.y() - min_xy.y()) / resolution_m)));
  if (static_cast<double>(width_) * height_ > 1e8) {
    throw std::invalid_argument("Canvas: image too large");
  }
  rgba_.resize(static_cast<size_t>(width_) * height_ * 4);
  for (size_t i = 0; i < rgba_.size(); i += 4) {
    rgba_[i] = background.r, rgba_[i + 1] = background.g, rgba_[i + 2] = background.b;
    rgba_[i + 3] = background.a;
  }
}

Eigen::Vector2d Canvas::toPixel(const Eigen::Vector2d& w) const {
  return Eigen::Vector2d((w.x() - min_.x()) / resolution_,
                         height_ - (w.y() - min_.y()) / resolution_);
}

Rgba Canvas::pixel(int col, int row) const {
  const uint8_t* p = &rgba_[(static_cast<size_t>(row) * width_ + col) * 4];
  return {p[0], p[1], p[2], p[3]};
}

void Canvas::blend(int col, int row, Rgba c) {
  if (col < 0 || row < 0 || col >= width_ || row >= height_) return;
  uint8_t* p = &rgba_[(static_cast<size_t>(row) * width_ + col) * 4];
  const int a = c.a;
  p[0] = static_cast<uint8_t>((c.r * a + p[0] * (255 - a) + 127) / 255);
  p[1] = static_cast<uint8_t>((c.g * a + p[1] * (255 - a) + 127) / 255);
  p[2] = static_cast<uint8_t>((c.b * a + p[2] * (255 - a) + 127) / 255);
  p[3] = static_cast<uint8_t>(std::max<int>(p[3], a));
}

template <class Inside>
void Canvas::fillWhere(double x0, double y0, double x1, double y1, Rgba color, Inside inside) {
  const int c0 = std::max(0, static_cast<int>(std::floor(x0)));
  const int c1 = std::min(width_ - 1, static_cast<int>(std::ceil(x1)));
  const int r0 = std::max(0, static_cast<int>(std::floor(y0)));
  const int r1 = std::min(height_ - 1, static_cast<int>(std::ceil(y1)));
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      if (inside(Eigen::Vector2d(c + 0.5, r + 0.5))) blend(c, r, color);
    }
  }
}

void Canvas::drawLine(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Rgba color,
                      double thickness_px) {
  const Eigen::Vector2d pa = toPixel(a), pb = toPixel(b);
  const double h = std::max(0.5, 0.5 * thickness_px);
  const Eigen::Vector2d lo = pa.cwiseMin(pb).array() - h, hi = pa.cwiseMax(pb).array() + h;
  fillWhere(lo.x(), lo.y(), hi.x(), hi.y(), color,
            [&](const Eigen::Vector2d& p) { return distanceToSegment(p, pa, pb) <= h; });
}

void Canvas::drawPolyline(const std::vector<Eigen::Vector2d>& pts, Rgba color, double thickness_px,
                          bool closed) {
  for (size_t i = 0; i + 1 < pts.size(); ++i) drawLine(pts[i], pts[i + 1], color, thickness_px);
  if (closed && pts.size() > 2) drawLine(pts.back(), pts.front(), color, thickness_px);
}

void Canvas::fillPolygon(const std::vector<Eigen::Vector2d>& pts, Rgba color) {
  if (pts.size() < 3) return;
  std::vector<Eigen::Vector2d> px;
  Eigen::Vector2d lo = toPixel(pts[0]), hi = lo;
  for (const auto& p : pts) {
    px.push_back(toPixel(p));
    lo = lo.cwiseMin(px.back()), hi = hi.cwiseMax(px.back());
  }
  fillWhere(lo.x(), lo.y(), hi.x(), hi.y(), color, [&](const Eigen::Vector2d& q) {
    bool in = false;
    for (size_t i = 0, j = px.size() - 1; i < px.size(); j = i++) {
      if ((px[i].y() > q.y()) != (px[j].y() > q.y()) &&
          q.x() <
              (px[j].x() - px[i].x()) * (q.y() - px[i].y()) / (px[j].y() - px[i].y()) + px[i].x()) {
        in = !in;
      }
    }
    return in;
  });
}

void Canvas::drawCircle(const Eigen::Vector2d& center, double radius_m, Rgba color,
                        double thickness_px) {
  const Eigen::Vector2d c = toPixel(center);
  const double r = radius_m / resolution_, h = std::max(0.5, 0.5 * thickness_px);
  fillWhere(c.x() - r - h, c.y() - r - h, c.x() + r + h, c.y() + r + h, color,
            [&](const Eigen::Vector2d& p) { return std::abs((p - c).norm() - r) <= h; });
}

void Canvas::fillCircle(const Eigen::Vector2d& center, double radius_m, Rgba color) {
  const Eigen::Vector2d c = toPixel(center);
  const double r = std::max(0.5, radius_m / resolution_);
  fillWhere(c.x() - r, c.y() - r, c.x() + r, c.y() + r, color,
            [&](const Eigen::Vector2d& p) { return (p - c).norm() <= r; });
}

void Canvas::drawText(const Eigen::Vector2d& top_left, const std::string& text, Rgba color,
                      int scale) {
  const Eigen::Vector2d p = toPixel(top_left);
  drawTextPx(static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y())), text,
             color, scale);
}

void Canvas::drawTextPx(int col, int row, const std::string& text, Rgba color, int scale) {
  scale = std::max(1, scale);
  for (size_t k = 0; k < text.size(); ++k) {
    const char ch = static_cast<char>(std::toupper(static_cast<unsigned char>(text[k])));
    const char* found = ch ? std::strchr(kGlyphChars, ch) : nullptr;
    if (!found) continue;  // space and unknown characters leave a blank cell
    const uint8_t* glyph = kGlyphs[found - kGlyphChars];
    const int x0 = col + static_cast<int>(k) * 6 * scale;
    for (int gy = 0; gy < 7; ++gy) {
      for (int gx = 0; gx < 5; ++gx) {
        if (!(glyph[gy] & (0x10 >> gx))) continue;
        for (int sy = 0; sy < scale; ++sy) {
          for (int sx = 0; sx < scale; ++sx)
            blend(x0 + gx * scale + sx, row + gy * scale + sy, color);
        }
      }
    }
  }
}

void Canvas::savePng(const std::string& path) const {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw std::runtime_error(path + ": cannot open for writing");
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
    throw std::runtime_error(path + ": PNG encoding failed");
  }
  png_init_io(png, f);
  png_set_IHDR(png, info, width_, height_, 8, PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int r = 0; r < height_; ++r) {
    png_write_row(png, const_cast<png_bytep>(&rgba_[static_cast<size_t>(r) * width_ * 4]));
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fclose(f) != 0) throw std::runtime_error(path + ": write failed");
}

}  // namespace tacs::viz
