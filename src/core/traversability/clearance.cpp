// Obstacle clearance of the tri-grid nodes (paper Sec. III-B-2, eq. 1): obstacle points are
// rasterised on a fine 2D grid aligned with the tri-grid, an exact Euclidean distance transform
// (Felzenszwalb and Huttenlocher, lower envelope of parabolas) gives every fine cell its distance
// to the nearest obstacle, and a node takes the minimum over the fine cells of its triangle.
#include <algorithm>
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

}  // namespace

ClearanceField::ClearanceField(const BucketedScan& scan, const TriGrid& grid,
                               const TraversabilityConfig& config, std::vector<NodeModel>* models,
                               std::vector<float>* buffer)
    : dist_(buffer) {
  const int sub = config.clearance_subdivision;
  const int fine = grid.cells() * sub;
  const double fine_res = grid.resolution() / sub;
  fine_ = fine;
  fine_res_ = fine_res;
  origin_ = grid.origin();
  cap_ = static_cast<float>(2.0 * config.max_range);
  // Free cells start at a large finite value (the parabola arithmetic needs finite numbers).
  const float far = 4.0f * static_cast<float>(fine) * static_cast<float>(fine);
  std::vector<float>& dist = *dist_;
  dist.assign(static_cast<size_t>(fine) * fine, far);
  bool any = false;
  std::vector<char> column_used(fine, 0);
  for (size_t k = 0; k < models->size(); ++k) {
    const NodeModel& m = (*models)[k];
    for (uint32_t a = 0; a < m.count; ++a) {
      const Eigen::Vector3f& p = scan.points[scan.order[m.begin + a]];
      if (scan.point_class[scan.order[m.begin + a]] != kObstaclePoint) continue;
      const int col = std::clamp(static_cast<int>((p.x() - grid.origin()) / fine_res), 0, fine - 1);
      const int row = std::clamp(static_cast<int>((p.y() - grid.origin()) / fine_res), 0, fine - 1);
      dist[static_cast<size_t>(row) * fine + col] = 0.0f;
      column_used[col] = 1;
      any = true;
    }
  }
  const float cap = cap_;
  if (!any) {
    dist.assign(dist.size(), far);
    for (NodeModel& m : *models) m.clearance = m.center_clearance = cap;
    return;
  }
  std::vector<float> f, z;
  std::vector<int> v;
  for (int col = 0; col < fine; ++col) {
    if (column_used[col]) edt1d(dist.data() + col, fine, fine, &f, &v, &z);  // else all free
  }
  for (int row = 0; row < fine; ++row)
    edt1d(dist.data() + static_cast<size_t>(row) * fine, fine, 1, &f, &v, &z);

  // Fine cells of each triangle (by the sector of their centre; diagonal cells go to both).
  std::vector<std::pair<int, int>> cells_of[4];
  for (int a = 0; a < sub; ++a) {
    for (int b = 0; b < sub; ++b) {
      const double dx = (b + 0.5) / sub - 0.5, dy = (a + 0.5) / sub - 0.5;
      const double ax = std::abs(dx), ay = std::abs(dy);
      const double eps = 1e-9;
      if (ax >= ay - eps) cells_of[dx >= 0 ? 0 : 2].emplace_back(a, b);
      if (ay >= ax - eps) cells_of[dy >= 0 ? 1 : 3].emplace_back(a, b);
    }
  }
  const int n = grid.cells();
  for (size_t k = 0; k < models->size(); ++k) {
    NodeModel& m = (*models)[k];
    const int cell = static_cast<int>(k / 4), tri = static_cast<int>(k % 4);
    const int row0 = (cell / n) * sub, col0 = (cell % n) * sub;
    float best = far;
    for (const auto& [a, b] : cells_of[tri]) {
      best = std::min(best, dist[static_cast<size_t>(row0 + a) * fine + col0 + b]);
    }
    m.clearance = std::min(cap, static_cast<float>(std::sqrt(best) * fine_res));
  }
  for (NodeModel& m : *models) m.center_clearance = at(m.position.x(), m.position.y());
}

float ClearanceField::at(double x, double y) const {
  const int col = static_cast<int>(std::floor((x - origin_) / fine_res_));
  const int row = static_cast<int>(std::floor((y - origin_) / fine_res_));
  if (col < 0 || row < 0 || col >= fine_ || row >= fine_) return cap_;
  const float d2 = (*dist_)[static_cast<size_t>(row) * fine_ + col];  // squared, in cells
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
