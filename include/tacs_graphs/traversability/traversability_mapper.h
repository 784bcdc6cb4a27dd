// Per-scan traversability mapping on a triangular grid (a port of the ideas of B-TMS, paper
// Sec. II-C and III-A) and the traversable / safe graph of paper Sec. III-B-2 (eq. 1).
//
// Pipeline of TraversabilityMapper::process():
//  1. Tri-grid field: square cells of `resolution` around the robot, each cut by both diagonals
//     into 4 triangular nodes; every point goes to one node.
//  2. Node terrain model: a plane fitted by iterative PCA to the lowest points of the node; the
//     node is GROUND (flat, thin, at a plausible height relative to the robot's floor), NONGROUND
//     or UNKNOWN (too few points, or points on a line).
//  3. Completion: the sensor's blind disc around the robot takes the plane through the ground
//     ring around it; other unobserved nodes are inferred by BGK (sparse kernel) from observed
//     neighbours when the evidence surrounds them (interpolation, never extrapolation past an
//     edge such as a drop-off). Inferred nodes carry `inferred = true` and a larger variance.
//  4. Obstacles: non-ground points between obstacle_min_height and robot_height above the local
//     ground; a 2D Euclidean distance transform gives each node its clearance (the distance from
//     its triangle to the nearest obstacle; 0 when an obstacle lies inside it).
//  5. Traversable graph: breadth-first search from the node under the robot over edge-adjacent
//     GROUND nodes that hold no obstacle and pass the local convexity/concavity test (normals
//     agree, no step); no re-seeding, so it is the robot's connected component only.
//  6. Safe graph (eq. 1): traversable nodes with clearance >= safe_clearance and the edges
//     between two safe nodes. Doorways narrower than about 2 * safe_clearance + resolution split
//     it, which is what separates rooms.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "tacs_graphs/common/types.h"
#include "tacs_graphs/traversability/traversability_config.h"

namespace tacs {

enum class TravLabel : uint8_t { kUnknown = 0, kGround = 1, kNonGround = 2 };

/// One triangular node of the tri-grid (or of the accumulated map).
struct TravNode {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // triangle centroid on the ground plane [m]
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   // ground plane normal, n_z >= 0
  TravLabel label = TravLabel::kUnknown;
  bool inferred = false;     // the plane was inferred (BGK / blind disc), not fitted to points
  float variance = 0.0f;     // variance of the ground height estimate [m^2]
  float clearance = 0.0f;    // 2D distance from the node's triangle to the nearest obstacle [m]
  bool traversable = false;  // in the robot's traversable graph
  bool safe = false;         // traversable and clearance >= safe_clearance (eq. 1)
};

/// Nodes and undirected edges (index pairs, first < second) of the traversable graph. Frame: the
/// base frame for one scan (TraversabilityMapper), the map frame when accumulated
/// (TraversableMap). Nodes that are not traversable are listed too (labels, clearance), but
/// edges only join two traversable nodes. The safe graph is the subgraph of safe nodes.
struct TravGraph {
  std::vector<TravNode> nodes;
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  int root = -1;  // node under the robot, -1 when none was found (per-scan graphs only)

  /// Edges between two safe nodes: the edge set E^safe of eq. 1.
  std::vector<std::pair<uint32_t, uint32_t>> safeEdges() const;
  size_t countTraversable() const;
  size_t countSafe() const;
  /// The graph moved from its frame b into frame a (node positions and normals).
  TravGraph transformed(const Pose3& T_a_b) const;
};

struct TraversabilityResult {
  TravGraph graph;
  PointCloud::Ptr ground;     // ground points of the scan (base frame, input intensity kept)
  PointCloud::Ptr obstacles;  // non-ground points in the obstacle band (base frame)
  double time_ms = 0.0;
  size_t ground_points = 0;
  size_t nonground_points = 0;  // every other valid point inside the grid
  /// Empty when all went well; otherwise human-readable reasons joined by "; " (empty scan, no
  /// ground under the robot, tilted ground, ...). The other fields are still valid.
  std::string warning;
};

/// Stateless per-scan mapper; process() is const and thread-compatible.
class TraversabilityMapper {
 public:
  /// Validates the config (throws ConfigError).
  explicit TraversabilityMapper(const TraversabilityConfig& config);

  /// `scan_in_base`: one scan in the gravity-aligned base frame (z up, robot at the origin).
  /// Non-finite points are skipped.
  TraversabilityResult process(const PointCloud& scan_in_base) const;

  const TraversabilityConfig& config() const { return config_; }

 private:
  TraversabilityConfig config_;
};

}  // namespace tacs
