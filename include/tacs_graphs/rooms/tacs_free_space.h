// Traversability-aware free-space segmentation (paper Sec. III-B-2, eq. 1-3).
//
// The room graph is the safe graph of the accumulated TraversableMap (eq. 1: traversable nodes at
// least lambda_o from obstacles, edges between two of them) with the edges through doorways cut.
// A doorway is an opening between two collinear wall landmarks of the same facing, between
// `min_doorway_width` and `max_doorway_width` wide: the safe graph alone splits at openings
// narrower than about 2 * lambda_o, the cut also splits wide openings (a gap in a half wall, a
// hall's 3 m entrances) whose sides are mapped as walls.
//
// Accumulation and trigger (eq. 2-3), evaluated once per keyframe:
//  - T_inside at keyframe k is the room-graph component at the robot's position, limited to
//    `local_radius` around it (the reach of one keyframe's local traversable graph, which is what
//    eq. 2 unites; it also keeps one observation of a long corridor loop from covering the loop).
//  - While the robot stays in the component of the keyframes accumulated so far, keyframe k
//    joins them (T_room grows).
//  - When the robot stands on no safe node (in a doorway or a narrow passage), the keyframe is
//    held: it joins no region, nothing is emitted.
//  - Accumulated keyframes in other components than the robot's are split off: the graph has
//    split between where the robot was and where it is (it went through a doorway, or a doorway
//    it passed was mapped since). Each such component is emitted as a region; the keyframes in
//    the robot's component go on accumulating, with keyframe k. An emitted T_room is the union
//    of the T_inside of its keyframes evaluated on the current room graph, so free space seen
//    through a door before the door was cut stays out.
//  - After `max_keyframes_per_observation` keyframes the region is also emitted (and restarted),
//    so a robot staying in one room still reports it; the room map merges the repeats.
// The emitted free space also holds the traversable nodes that are too close to walls or
// furniture to be safe, within `border_distance` of the room's safe nodes (reached without
// crossing a doorway), so a room's free space reaches its walls as its floor does.
// flush() emits what is accumulated (end of a sequence).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "tacs_graphs/rooms/rooms_config.h"
#include "tacs_graphs/traversability/traversable_map.h"
#include "tacs_graphs/walls/wall_map.h"

namespace tacs {

/// An opening in a wall line: the segment from a to b on the wall face (map xy).
struct Doorway {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  uint32_t wall_a = 0, wall_b = 0;  // the landmarks on either side
  double width() const { return (b - a).norm(); }
};

/// Openings between collinear same-facing wall landmarks (see the file comment).
std::vector<Doorway> findDoorways(const std::map<uint32_t, WallLandmark>& landmarks,
                                  const TacsFreeSpaceConfig& config);

/// A finished free-space region: T_room of eq. 3 and the keyframes accumulated into it.
struct FreeSpaceRegion {
  std::vector<Eigen::Vector3d> points;  // map-frame node positions
  std::vector<uint32_t> keyframe_ids;
  std::vector<Eigen::Vector3d> keyframe_positions;  // the robot's, in keyframe_ids order
};

class TacsFreeSpace {
 public:
  struct StepResult {
    bool inside = false;                    // the robot is on a safe node (T_inside is not empty)
    size_t inside_nodes = 0;                // size of T_inside
    size_t doorways = 0;                    // doorways cut in the room graph
    std::vector<FreeSpaceRegion> finished;  // regions emitted at this keyframe
  };

  /// Validates the config (throws ConfigError).
  explicit TacsFreeSpace(const TacsFreeSpaceConfig& config);

  /// One keyframe: the robot (base_link, on the floor) at `robot_position` in the map frame.
  StepResult step(uint32_t keyframe_id, const Eigen::Vector3d& robot_position,
                  const TraversableMap& map, const std::map<uint32_t, WallLandmark>& landmarks);

  /// Emits the accumulated region, if any.
  std::optional<FreeSpaceRegion> flush(const TraversableMap& map,
                                       const std::map<uint32_t, WallLandmark>& landmarks);

  size_t accumulatedKeyframes() const { return accumulated_.size(); }

 private:
  struct Labels {
    std::vector<int> label;       // component of each map node in the room graph, -1: not safe
    std::vector<char> edge_open;  // per map edge: 0 when it goes through a doorway
    size_t doorways = 0;
  };
  Labels labelRoomGraph(const TraversableMap& map,
                        const std::map<uint32_t, WallLandmark>& landmarks) const;
  int labelAt(const TraversableMap& map, const Labels& labels, const Eigen::Vector3d& p) const;
  struct Accumulated {
    uint32_t keyframe_id;
    Eigen::Vector3d position;
  };
  std::optional<FreeSpaceRegion> emit(const TraversableMap& map, const Labels& labels,
                                      const std::vector<Accumulated>& keyframes);
  void attachBorder(const TravGraph& g, const Labels& labels, std::vector<char>* in_room) const;

  TacsFreeSpaceConfig config_;
  std::vector<Accumulated> accumulated_;
};

}  // namespace tacs
