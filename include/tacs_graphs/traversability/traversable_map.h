// Accumulation of per-keyframe traversable graphs into one map-frame graph (the input of room
// segmentation, paper Sec. III-B-2 and eq. 2: the room graph is a union of per-time graphs).
//
// Nodes of overlapping keyframe graphs are merged by position: a 2D hash on the map-frame node
// centres with cells of `map_resolution`; inside a cell, nodes closer than `map_merge_height` in
// z are one node (so levels of a building stay apart). A merged node keeps
//  - the label, position, normal and variance of its best observation (traversable first, then
//    a known label, then observed before inferred, then the lowest variance),
//  - the minimum clearance over observations (obstacles seen from any viewpoint count),
//  - traversable if any keyframe found it traversable; safe = traversable and
//    clearance >= safe_clearance (eq. 1),
// and the edge set is the union of the keyframes' edges.
// Keyframe graphs are kept (without their UNKNOWN nodes) so the map can be rebuilt when the
// backend moves keyframes (updatePoses), which is how optimised poses improve the rooms.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "tacs_graphs/common/types.h"
#include "tacs_graphs/traversability/traversability_mapper.h"

namespace tacs {

class TraversableMap {
 public:
  /// Uses map_resolution, map_merge_height and safe_clearance. Validates the config.
  explicit TraversableMap(const TraversabilityConfig& config);

  /// Adds the graph of one keyframe (base frame) at pose T_map_base. Inserting a keyframe id
  /// again replaces its graph (the map is rebuilt).
  void insert(const TravGraph& graph_in_base, const Pose3& T_map_base, uint32_t keyframe_id);

  /// Moves keyframes to new poses and rebuilds the map; ids not in `poses` keep their pose.
  void updatePoses(const std::map<uint32_t, Pose3>& poses);

  void clear();

  /// The merged graph in the map frame (root = -1).
  const TravGraph& graph() const { return graph_; }
  /// Keyframes whose local graphs are held (the others were released by map_retention).
  size_t keyframeCount() const { return keyframes_.size(); }
  /// Number of keyframe observations merged into node i.
  uint32_t observations(uint32_t i) const { return stats_[i].observations; }
  /// Id of the last keyframe that observed node i.
  uint32_t lastKeyframe(uint32_t i) const { return stats_[i].last_keyframe; }

  /// Nodes whose centre lies within `radius` of `center` in the xy plane (any height).
  std::vector<uint32_t> nodesWithin(const Eigen::Vector3d& center, double radius) const;

  /// Connected components of the safe graph (safe nodes, edges between two safe nodes), largest
  /// first; each lists node indices.
  std::vector<std::vector<uint32_t>> safeComponents() const;

  /// The component containing the node nearest to `position` (within 2 map cells in xy, nearest
  /// in z), in the safe graph or, with safe_only = false, in the traversable graph. Empty when no
  /// such node is near.
  std::vector<uint32_t> componentAt(const Eigen::Vector3d& position, bool safe_only = true) const;

 private:
  struct Stats {
    uint32_t observations = 0;
    uint32_t last_keyframe = 0;
  };
  struct Keyframe {
    Pose3 T_map_base = Pose3::Identity();
    TravGraph graph;  // base frame, without UNKNOWN nodes
  };

  void merge(const Keyframe& keyframe, uint32_t keyframe_id);
  void rebuild();
  int64_t cellKey(int64_t ix, int64_t iy) const { return (ix << 32) ^ (iy & 0xffffffff); }
  uint32_t findOrAdd(const TravNode& node, uint32_t keyframe_id);
  bool keep(uint32_t i, bool safe_only) const;
  std::vector<std::vector<uint32_t>> adjacency(bool safe_only) const;

  TraversabilityConfig config_;
  std::map<uint32_t, Keyframe> keyframes_;
  KeyframeRetention retention_;
  TravGraph graph_;
  std::vector<Stats> stats_;
  std::unordered_map<int64_t, std::vector<uint32_t>> cells_;
  std::unordered_set<uint64_t> edge_keys_;
};

}  // namespace tacs
