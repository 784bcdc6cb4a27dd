// A static 3-D KD-tree for the nearest-point and k-nearest searches of GICP (covariances,
// correspondences). Built once per cloud and then only read, so it is laid out for reading:
// the points are copied in leaf order, each leaf's points contiguous in memory, and a search
// descends by one coordinate comparison per node. Distances are computed in float (centimetre
// scan data loses nothing) as dx^2 + dy^2 + dz^2, left to right, so they are the same numbers
// on every build.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace tacs {

class KdTree3 {
 public:
  /// Leaves hold at most this many points: shallow enough to build fast, small enough that a
  /// leaf scan stays cheap.
  static constexpr int kLeafSize = 32;

  explicit KdTree3(const std::vector<Eigen::Vector3d>& points);

  size_t size() const { return ids_.size(); }

  /// Index of the nearest point with squared distance below `bound_sq` (strictly), or -1; its
  /// squared distance in *dist_sq (`bound_sq` when none). A hint (original index of a likely
  /// answer, e.g. the last iteration's) tightens the bound from the start.
  int64_t nearest(const Eigen::Vector3f& query, float bound_sq, float* dist_sq,
                  int64_t hint = -1) const;

  /// Up to k nearest points, closest first (a point tied with the k-th is left out); returns
  /// how many were found.
  size_t knn(const Eigen::Vector3f& query, size_t k, uint32_t* indices, float* dist_sq) const;

  /// The point of original index i, as the tree stores it (float).
  Eigen::Vector3f point(uint32_t i) const;

 private:
  // An inner node splits on `axis` (children a and b, their points' extents on that axis ending
  // at left_max and starting at right_min); a leaf (axis == kLeaf) holds the leaf-ordered
  // points [a, b).
  struct Node {
    float left_max = 0.0f;
    float right_min = 0.0f;
    uint32_t axis = 0;
    uint32_t a = 0;  // inner: left child; leaf: first point
    uint32_t b = 0;  // inner: right child; leaf: one past the last point
  };
  static constexpr uint32_t kLeaf = 3;

  /// Node over points[order[begin..end)], whose box is [lo, hi].
  uint32_t build(std::vector<uint32_t>& order, uint32_t begin, uint32_t end,
                 const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3f& lo,
                 const Eigen::Vector3f& hi);
  /// `offset`: per axis, the query's gap to the current cell (0 inside); `cell_sq` their sum of
  /// squares, a lower bound on the distance to any point of the cell.
  template <class Result>
  void search(uint32_t node, const float* q, float* offset, float cell_sq, Result& result) const;

  /// The query's per-axis gaps to the cloud's bounding box and their sum of squares: queries
  /// outside the cloud (a scan turned by a wrong hypothesis) start with a tight bound.
  float rootGap(const Eigen::Vector3f& query, float* offset) const;

  std::vector<Node> nodes_;
  Eigen::Vector3f lo_, hi_;       // bounding box of all points
  std::vector<float> x_, y_, z_;  // leaf-ordered point coordinates, one array per axis
  std::vector<uint32_t> ids_;     // original index of each leaf-ordered point
  std::vector<uint32_t> where_;   // leaf-ordered position of each original index
};

}  // namespace tacs
