// Obstacle clearance of the tri-grid nodes (paper Sec. III-B-2, eq. 1): obstacle points are
// rasterised on a fine 2D grid aligned with the tri-grid, an exact Euclidean distance transform
// (Felzenszwalb and Huttenlocher, lower envelope of parabolas) gives every fine cell its distance
// to the nearest obstacle, and a node takes the minimum over the fine cells of its triangle.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "tri_grid.h"

namespace tacs::trav {

namespace {

// 1D squared distance transform of f (size n, stride `stride` in data) in place.
void edt1d(float* data, int n, int stride, std::vector<float>* f, std::vector<int>* v,
           std::vector<float>* z) {
  f->resize(n);
  v->resize(n);
  z->resize(n + 1);
  for (int q = 0; q < n; ++q) (*f)[q] = data[q * stride];
  int k = 0;
  (*v)[0] = 0;
  (*z)[0] = -std::numeric_limits<float>::infinity();
  (*z)[1] = std::numeric_limits<float>::infinity();
  for (int q = 1; q < n; ++q) {
    auto intersect = [&](int p) {
      return (((*f)[q] + static_cast<float>(q) * q) - ((*f)[p] + static_cast<float>(p) * p)) /
             (2.0f * static_cast<float>(q - p));
    };
    float s = intersect((*v)[k]);
    while (s <= (*z)[k]) s = intersect((*v)[--k]);  // z[0] = -inf stops the loop
    ++k;
    (*v)[k] = q;
    (*z)[k] = s;
    (*z)[k + 1] = std::numeric_limits<float>::infinity();
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while ((*z)[k + 1] < q) ++k;
    const float dq = static_cast<float>(q - (*v)[k]);
    data[q * stride] = dq * dq + (*f)[(*v)[k]];
  }
}

// Rows r0..r1 and columns c0..c1 of the grid cells holding a node with content (all 0 if none).
std::array<int, 4> contentBox(const std::vector<NodeModel>& models, int n) {
  int r0 = n, r1 = -1, c0 = n, c1 = -1;
  for (size_t k = 0; k < models.size(); ++k) {
    if (!hasContent(models[k])) continue;
    const int cell = static_cast<int>(k / 4);
    r0 = std::min(r0, cell / n);
    r1 = std::max(r1, cell / n);
    c0 = std::min(c0, cell % n);
    c1 = std::max(c1, cell % n);
  }
  if (r1 < 0) return {0, 0, 0, 0};
  return {r0, r1, c0, c1};
}

// The (row, column) fine cells of each of a cell's four triangles, `sub` x `sub` fine cells a
// cell, by the sector of their centre; diagonal cells go to both triangles.
std::array<std::vector<std::pair<int, int>>, 4> fineCellsOfTriangles(int sub) {
  std::array<std::vector<std::pair<int, int>>, 4> cells_of;
  for (int a = 0; a < sub; ++a) {
    for (int b = 0; b < sub; ++b) {
      const double dx = (b + 0.5) / sub - 0.5, dy = (a + 0.5) / sub - 0.5;
      const double ax = std::abs(dx), ay = std::abs(dy);
      const double eps = 1e-9;
      if (ax >= ay - eps) cells_of[dx >= 0 ? 0 : 2].emplace_back(a, b);
      if (ay >= ax - eps) cells_of[dy >= 0 ? 1 : 3].emplace_back(a, b);
    }
  }
  return cells_of;
}

}  // namespace

ClearanceField::ClearanceField(const BucketedScan& scan, const TriGrid& grid,
                               const TraversabilityConfig& config, std::vector<NodeModel>* models,
                               std::vector<float>* buffer)
    : dist_(buffer) {
  const int sub = config.clearance_subdivision;
  const int n = grid.cells();
  const double fine_res = grid.resolution() / sub;
  fine_res_ = fine_res;
  cap_ = static_cast<float>(2.0 * config.max_range);
  // The transform runs on the bounding box of the nodes with content only (every obstacle point
  // and every node that can be queried lies in it): exact there, and indoors much smaller.
  const auto [r0, r1, c0, c1] = contentBox(*models, n);
  rows_ = (r1 - r0 + 1) * sub;
  cols_ = (c1 - c0 + 1) * sub;
  x0_ = grid.origin() + c0 * grid.resolution();
  y0_ = grid.origin() + r0 * grid.resolution();
  // Free cells start at a large finite value (the parabola arithmetic needs finite numbers).
  const float far = 4.0f * static_cast<float>(n * sub) * static_cast<float>(n * sub);
  std::vector<float>& dist = *dist_;
  dist.assign(static_cast<size_t>(rows_) * cols_, far);
  bool any = false;
  std::vector<char> column_used(cols_, 0);
  for (size_t i = 0; i < scan.points.size(); ++i) {
    if (scan.node_of[i] < 0 || scan.point_class[i] != kObstaclePoint) continue;
    const Eigen::Vector3f& p = scan.points[i];
    const int col = std::clamp(static_cast<int>((p.x() - x0_) / fine_res), 0, cols_ - 1);
    const int row = std::clamp(static_cast<int>((p.y() - y0_) / fine_res), 0, rows_ - 1);
    dist[static_cast<size_t>(row) * cols_ + col] = 0.0f;
    column_used[col] = 1;
    any = true;
  }
  const float cap = cap_;
  if (!any) {
    for (NodeModel& m : *models) m.clearance = m.center_clearance = cap;
    return;
  }
  std::vector<float> f, z;
  std::vector<int> v;
  for (int col = 0; col < cols_; ++col) {
    if (column_used[col]) edt1d(dist.data() + col, rows_, cols_, &f, &v, &z);  // else all free
  }
  for (int row = 0; row < rows_; ++row) {
    edt1d(dist.data() + static_cast<size_t>(row) * cols_, cols_, 1, &f, &v, &z);
  }

  const std::array<std::vector<std::pair<int, int>>, 4> cells_of = fineCellsOfTriangles(sub);
  for (size_t k = 0; k < models->size(); ++k) {
    NodeModel& m = (*models)[k];
    if (!hasContent(m)) {
      m.clearance = m.center_clearance = cap;  // never output nor entered
      continue;
    }
    const int cell = static_cast<int>(k / 4), tri = static_cast<int>(k % 4);
    const int row0 = (cell / n - r0) * sub, col0 = (cell % n - c0) * sub;
    float best = far;
    for (const auto& [a, b] : cells_of[tri]) {
      best = std::min(best, dist[static_cast<size_t>(row0 + a) * cols_ + col0 + b]);
    }
    m.clearance = std::min(cap, static_cast<float>(std::sqrt(best) * fine_res));
    m.center_clearance = at(m.position.x(), m.position.y());
  }
}

float ClearanceField::at(double x, double y) const {
  const int col = static_cast<int>(std::floor((x - x0_) / fine_res_));
  const int row = static_cast<int>(std::floor((y - y0_) / fine_res_));
  if (col < 0 || row < 0 || col >= cols_ || row >= rows_ || dist_->empty()) return cap_;
  const float d2 = (*dist_)[static_cast<size_t>(row) * cols_ + col];  // squared, in cells
  return std::min(cap_, static_cast<float>(std::sqrt(d2) * fine_res_));
}

bool ClearanceField::segmentClear(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                  double min_clearance) const {
  // Sample at half a fine cell so no cell the segment crosses is skipped.
  const int steps = 1 + static_cast<int>((b - a).norm() / (0.5 * fine_res_));
  for (int i = 0; i <= steps; ++i) {
    const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(i) / steps);
    if (at(p.x(), p.y()) <= min_clearance) return false;
  }
  return true;
}

}  // namespace tacs::trav
