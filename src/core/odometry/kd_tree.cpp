#include "tacs_graphs/odometry/kd_tree.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <tuple>
#include <utility>

namespace tacs {

namespace {

inline float squaredDistance(const float* a, const float* b) {
  const float dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return dx * dx + dy * dy + dz * dz;
}

// The closest point strictly below a bound.
struct NearestResult {
  float worst;
  int64_t index = -1;
  float bound() const { return worst; }
  void offer(float d, uint32_t id) {
    if (d < worst) worst = d, index = id;
  }
};

// The k closest points, sorted; a point is taken only when strictly closer than the k-th.
struct KnnResult {
  size_t k;
  uint32_t* ids;
  float* dist;
  size_t count = 0;
  float bound() const { return count < k ? std::numeric_limits<float>::max() : dist[k - 1]; }
  void offer(float d, uint32_t id) {
    if (d >= bound()) return;
    size_t i = count < k ? count++ : k - 1;
    for (; i > 0 && dist[i - 1] > d; --i) dist[i] = dist[i - 1], ids[i] = ids[i - 1];
    dist[i] = d;
    ids[i] = id;
  }
};

}  // namespace

namespace {

// The bounding box of points[order[begin..end)].
std::pair<Eigen::Vector3f, Eigen::Vector3f> boundsOf(const std::vector<uint32_t>& order,
                                                     uint32_t begin, uint32_t end,
                                                     const std::vector<Eigen::Vector3f>& points) {
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::max());
  Eigen::Vector3f hi = -lo;
  for (uint32_t i = begin; i < end; ++i) {
    lo = lo.cwiseMin(points[order[i]]);
    hi = hi.cwiseMax(points[order[i]]);
  }
  return {lo, hi};
}

}  // namespace

KdTree3::KdTree3(const std::vector<Eigen::Vector3d>& points) {
  const uint32_t n = static_cast<uint32_t>(points.size());
  std::vector<Eigen::Vector3f> floats(n);
  for (uint32_t i = 0; i < n; ++i) floats[i] = points[i].cast<float>();
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  nodes_.reserve(2 * (n / kLeafSize + 1));
  std::tie(lo_, hi_) = boundsOf(order, 0, n, floats);
  if (n > 0) build(order, 0, n, floats, lo_, hi_);
  for (auto* axis : {&x_, &y_, &z_}) axis->resize(n);
  where_.resize(n);
  for (uint32_t pos = 0; pos < n; ++pos) {
    const Eigen::Vector3f& p = floats[order[pos]];
    x_[pos] = p.x();
    y_[pos] = p.y();
    z_[pos] = p.z();
    where_[order[pos]] = pos;
  }
  ids_ = std::move(order);
}

uint32_t KdTree3::build(std::vector<uint32_t>& order, uint32_t begin, uint32_t end,
                        const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3f& lo,
                        const Eigen::Vector3f& hi) {
  const uint32_t index = static_cast<uint32_t>(nodes_.size());
  nodes_.emplace_back();
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  // A leaf when small, or when all points coincide, whatever its size.
  if (end - begin <= static_cast<uint32_t>(kLeafSize) || !(hi[axis] > lo[axis])) {
    nodes_[index].axis = kLeaf;
    nodes_[index].a = begin;
    nodes_[index].b = end;
    return index;
  }
  // Split the widest axis at the middle of the points' extent (not at their median): cells stay
  // compact where the cloud is dense and large where it is sparse, which prunes a search better
  // on LiDAR clouds than a balanced tree of long thin cells.
  auto coordinate = [&](uint32_t i) { return points[i][axis]; };
  const float cut = 0.5f * (lo[axis] + hi[axis]);
  uint32_t mid =
      static_cast<uint32_t>(std::partition(order.begin() + begin, order.begin() + end,
                                           [&](uint32_t i) { return coordinate(i) < cut; }) -
                            order.begin());
  if (mid == begin || mid == end) {  // extent of a few float steps: the cut rounds to an end
    mid = begin + (end - begin) / 2;
    std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                     [&](uint32_t i, uint32_t j) { return coordinate(i) < coordinate(j); });
  }
  // The children's boxes; their extents on the split axis go into the node: a far child whose
  // points start well beyond the cut is pruned sooner.
  const auto [left_lo, left_hi] = boundsOf(order, begin, mid, points);
  const auto [right_lo, right_hi] = boundsOf(order, mid, end, points);
  const uint32_t left = build(order, begin, mid, points, left_lo, left_hi);
  const uint32_t right = build(order, mid, end, points, right_lo, right_hi);
  Node& node = nodes_[index];  // after the recursion: nodes_ may have grown
  node.left_max = left_hi[axis];
  node.right_min = right_lo[axis];
  node.axis = static_cast<uint32_t>(axis);
  node.a = left;
  node.b = right;
  return index;
}

template <class Result>
void KdTree3::search(uint32_t index, const float* q, float* offset, float cell_sq,
                     Result& result) const {
  const Node& node = nodes_[index];
  if (node.axis == kLeaf) {
    // The leaf's distances first, in a loop the compiler vectorises (coordinates stored axis by
    // axis), then the few below the bound offered one by one. A leaf of coinciding points may
    // exceed kLeafSize: it is taken in chunks.
    float dist[kLeafSize];
    for (uint32_t begin = node.a; begin < node.b; begin += kLeafSize) {
      const uint32_t n = std::min<uint32_t>(kLeafSize, node.b - begin);
      const float *xs = &x_[begin], *ys = &y_[begin], *zs = &z_[begin];
      for (uint32_t j = 0; j < n; ++j) {
        const float dx = q[0] - xs[j], dy = q[1] - ys[j], dz = q[2] - zs[j];
        dist[j] = dx * dx + dy * dy + dz * dz;
      }
      for (uint32_t j = 0; j < n; ++j) {
        if (dist[j] < result.bound()) result.offer(dist[j], ids_[begin + j]);
      }
    }
    return;
  }
  // The left child's points have coordinates <= left_max on this axis, the right child's
  // >= right_min; the query descends first into the side it is nearer to. The far child's cell
  // lies at least as far as the near cell's bound with this axis's gap replaced (Arya and
  // Mount's incremental distance): it is searched only when it may hold a closer point.
  const float past_left = q[node.axis] - node.left_max;
  const float past_right = q[node.axis] - node.right_min;
  const bool left_first = past_left + past_right < 0.0f;
  const uint32_t near = left_first ? node.a : node.b;
  const uint32_t far = left_first ? node.b : node.a;
  const float gap = left_first ? std::max(0.0f, -past_right) : std::max(0.0f, past_left);
  search(near, q, offset, cell_sq, result);
  const float old = offset[node.axis];
  const float far_sq = cell_sq - old * old + gap * gap;
  if (far_sq < result.bound()) {
    offset[node.axis] = gap;
    search(far, q, offset, far_sq, result);
    offset[node.axis] = old;
  }
}

int64_t KdTree3::nearest(const Eigen::Vector3f& query, float bound_sq, float* dist_sq,
                         int64_t hint) const {
  NearestResult result{bound_sq};
  if (hint >= 0 && static_cast<size_t>(hint) < where_.size()) {
    // Only strictly closer points replace it: the bound is the hint's own float distance.
    result.offer(squaredDistance(query.data(), point(static_cast<uint32_t>(hint)).data()),
                 static_cast<uint32_t>(hint));
  }
  float offset[3];
  const float cell_sq = rootGap(query, offset);
  if (!nodes_.empty() && cell_sq < result.bound()) search(0, query.data(), offset, cell_sq, result);
  if (dist_sq) *dist_sq = result.worst;
  return result.index;
}

size_t KdTree3::knn(const Eigen::Vector3f& query, size_t k, uint32_t* indices,
                    float* dist_sq) const {
  KnnResult result{k, indices, dist_sq};
  float offset[3];
  const float cell_sq = rootGap(query, offset);
  if (k > 0 && !nodes_.empty()) search(0, query.data(), offset, cell_sq, result);
  return result.count;
}

float KdTree3::rootGap(const Eigen::Vector3f& query, float* offset) const {
  float sum = 0.0f;
  for (int d = 0; d < 3; ++d) {
    offset[d] = std::max({0.0f, lo_[d] - query[d], query[d] - hi_[d]});
    sum += offset[d] * offset[d];
  }
  return sum;
}

Eigen::Vector3f KdTree3::point(uint32_t i) const {
  const uint32_t pos = where_[i];
  return Eigen::Vector3f(x_[pos], y_[pos], z_[pos]);
}

}  // namespace tacs
