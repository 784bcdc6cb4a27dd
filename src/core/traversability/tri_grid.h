// Internal building blocks of TraversabilityMapper: the tri-grid geometry, the per-node terrain
// model, the BGK completion and the obstacle clearance. Not part of the public interface.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "tacs_graphs/traversability/traversability_mapper.h"

namespace tacs::trav {

/// Square grid of `cells x cells` cells centred on the robot; each cell is cut by both diagonals
/// into 4 triangles: 0 = +x side, 1 = +y, 2 = -x, 3 = -y. Node id = cell * 4 + triangle, with
/// cell = row * cells + col (row along y, col along x).
class TriGrid {
 public:
  TriGrid(double resolution, double max_range);

  int cells() const { return cells_; }
  size_t size() const { return static_cast<size_t>(cells_) * cells_ * 4; }
  double resolution() const { return res_; }
  double origin() const { return origin_; }  // x (and y) of the grid's lower-left corner [m]

  /// Node containing (x, y), -1 outside the grid.
  int nodeAt(double x, double y) const;
  /// Centroid of the node's triangle (x, y) [m].
  Eigen::Vector2d centroid(int node) const;
  /// The 3 edge-adjacent neighbours (2 siblings in the cell, 1 across the cell edge); -1 outside.
  void neighbours(int node, int out[3]) const;

 private:
  double res_;
  int cells_;
  double origin_;
};

/// Terrain model of one node.
struct NodeModel {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double d = 0.0;                                      // plane n . p + d = 0
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // centroid, z on the plane
  TravLabel label = TravLabel::kUnknown;
  bool has_plane = false;  // normal/d are meaningful (fitted or inferred)
  bool inferred = false;
  float variance = 0.0f;
  uint32_t begin = 0, count = 0;  // range in the node-sorted point order
  float clearance = 0.0f;         // from the triangle (nearest point of it) [m]
  float center_clearance = 0.0f;  // from the centroid [m]

  double heightAt(double x, double y) const {
    return normal.z() > 1e-6 ? -(d + normal.x() * x + normal.y() * y) / normal.z() : position.z();
  }
  double distance(const Eigen::Vector3f& p) const { return normal.dot(p.cast<double>()) + d; }
  bool isGround() const { return label == TravLabel::kGround; }
};

/// A node with points or an inferred plane (the others are empty and never in a graph).
inline bool hasContent(const NodeModel& m) { return m.count > 0 || m.inferred; }

/// Valid points of a scan bucketed by node (counting sort): points of node i are
/// points[order[models[i].begin .. begin + count)].
struct BucketedScan {
  std::vector<Eigen::Vector3f> points;
  std::vector<int> node_of;  // per point, -1 when dropped (non-finite, too close, outside)
  std::vector<uint32_t> order;
  std::vector<uint32_t> counts, fill;  // counting-sort buffers
  std::vector<uint8_t> point_class;    // per point, set by classifyPoints()
  size_t valid = 0;
};

/// Kernel-weighted evidence gathered at one unobserved node (BGK).
struct Evidence {
  double ground = 0.0, nonground = 0.0;  // kernel mass of GROUND / NONGROUND neighbours
  double z = 0.0, zz = 0.0;              // sums of k * (neighbour plane height at the target)
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double sector[8] = {0, 0, 0, 0, 0, 0, 0, 0};  // ground mass per direction octant
};

/// Buffers kept between scans (one per thread): a scan then allocates no large block, which
/// matters because fresh pages cost more than the computation.
struct Workspace {
  std::vector<NodeModel> models;
  BucketedScan scan;
  std::vector<int> slot;
  std::vector<Evidence> evidence;
  std::vector<float> distance;
  std::vector<char> reached;
};

void bucketScan(const PointCloud& scan, const TriGrid& grid, const TraversabilityConfig& config,
                BucketedScan* out, std::vector<NodeModel>* models);

/// Fits the ground plane of every node with enough points by iterative PCA from its lowest
/// points and labels it (paper Sec. II-C; slope, thickness, height gates).
void fitNodePlanes(const BucketedScan& scan, const TriGrid& grid,
                   const TraversabilityConfig& config, std::vector<NodeModel>* models);

/// Fills the sensor's blind disc under the robot with the plane through the ground ring around
/// it, but not behind an obstacle inside the disc. Returns the blind radius found (0 when none
/// was filled).
double fillBlindDisc(const TriGrid& grid, const TraversabilityConfig& config,
                     std::vector<NodeModel>* models);

/// BGK completion: infers GROUND planes of unobserved nodes surrounded by observed evidence.
void inferUnobserved(const TriGrid& grid, const TraversabilityConfig& config,
                     std::vector<NodeModel>* models, std::vector<int>* slot,
                     std::vector<Evidence>* evidence);

enum PointClass : uint8_t { kOtherPoint = 0, kGroundPoint = 1, kObstaclePoint = 2 };

/// Classifies every bucketed point as ground, obstacle or other (BucketedScan::point_class). A
/// point of a node without ground may be ground at the height of observed ground next to it.
void classifyPoints(const TriGrid& grid, const std::vector<NodeModel>& models,
                    const TraversabilityConfig& config, BucketedScan* scan);

/// True for a ground point of a node with a ground plane.
bool isGroundPoint(const NodeModel& m, const Eigen::Vector3f& p, const TraversabilityConfig& c);
/// True for a point in the obstacle band above the local ground (not a ground point).
bool isObstaclePoint(const NodeModel& m, const Eigen::Vector3f& p, const TraversabilityConfig& c);

/// Distance to the nearest obstacle point on a fine 2D grid aligned with the tri-grid.
class ClearanceField {
 public:
  /// Rasterises the obstacle points of the nodes and runs a 2D Euclidean distance transform
  /// into `buffer` (kept by the caller); sets NodeModel::clearance and center_clearance.
  ClearanceField(const BucketedScan& scan, const TriGrid& grid, const TraversabilityConfig& config,
                 std::vector<NodeModel>* models, std::vector<float>* buffer);
  /// Distance from the fine cell containing (x, y) to the nearest obstacle cell [m].
  float at(double x, double y) const;
  /// True when every point of the segment a-b is more than `min_clearance` from obstacles.
  bool segmentClear(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double min_clearance) const;

 private:
  int rows_ = 0, cols_ = 0;  // fine cells of the bounding box of the nodes with content
  double fine_res_ = 0.0, x0_ = 0.0, y0_ = 0.0;
  float cap_ = 0.0f;
  std::vector<float>* dist_;  // metres
};

/// Local convexity/concavity test of the edge s-t: normals agree and no step across it.
bool lccPasses(const NodeModel& s, const NodeModel& t, const TraversabilityConfig& config);

}  // namespace tacs::trav
