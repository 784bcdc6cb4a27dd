// Wall landmarks in the map frame and the association of wall observations to them.
//
// An observation (a WallSegment in the base frame) is moved to the map with the keyframe pose and
// matched to the landmark on the same side of the same plane whose extent it overlaps or nearly
// touches along the wall, unless a partition meets the wall between them (then they are the walls
// of two rooms); otherwise it starts a new landmark. Matched landmarks grow their extent.
// Because extents grow, two landmarks can come to describe one wall (a wall first seen in two
// pieces); mergeDuplicates() folds them and reports which id went into which, so the backend can
// move the removed landmark's factors to the kept one.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "tacs_graphs/common/types.h"
#include "tacs_graphs/scene_graph/scene_graph.h"
#include "tacs_graphs/walls/wall_segment.h"

namespace tacs {

struct WallLandmark {
  uint32_t id = 0;
  /// Unit normal in the map frame, facing the side the wall was observed from.
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  /// n.p + d = 0 in the map frame (m).
  double d = 0.0;
  /// Extent on the plane's line in the map xy plane (m), ordered along wallAxis(normal).
  Eigen::Vector2d endpoints[2] = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  /// Height range (m, map frame).
  double z_min = 0.0;
  double z_max = 0.0;
  /// Inlier-weighted mean of the observations' tops (m, map frame): how high the face is seen to
  /// reach, robust to one observation whose plane took in the wall behind.
  double mean_top = 0.0;
  /// Observations associated (including those of merged landmarks).
  uint32_t observations = 0;
  /// Sum of the inliers of those observations: the weight of the running plane average.
  uint64_t inliers = 0;

  double length() const { return (endpoints[1] - endpoints[0]).norm(); }
  Eigen::Vector2d midpoint() const { return 0.5 * (endpoints[0] + endpoints[1]); }
};

struct WallAssociationConfig {
  /// Largest angle between the normals of an observation and its landmark (deg). Opposite
  /// normals (the two faces of one wall) never match.
  double max_normal_angle_deg = 10.0;
  /// Largest distance between the planes, measured at the segments' midpoints (m).
  double max_plane_distance = 0.3;
  /// Largest gap along the wall between the observation's and the landmark's extents (m);
  /// negative gaps are overlaps. Keep it below a door width to keep walls of two rooms apart.
  double max_gap = 0.5;
  /// Landmark planes are the inlier-weighted average of their observations until
  /// updateLandmarkPlane() sets them; with false they keep the plane of their first observation.
  bool average_planes = true;
  /// Landmarks shorter than this are no walls of the scene graph (m): pillar faces, the sides of
  /// cabinets and boxes. They stay landmarks (plane factors) and become walls if they grow.
  double min_wall_length = 1.0;
  /// Landmarks observed from fewer keyframes are no walls yet: one view of a plane can be the
  /// face of a machine, a stack of boxes or a plane through clutter. On the real hand-held hall,
  /// such landmarks (1-2 observations, < 200 inliers) came and went with millimetre changes of
  /// the poses, while the hall's walls had 26-160 observations.
  int min_wall_observations = 3;

  template <class V>
  void visit(V& v) {
    v("max_normal_angle_deg", max_normal_angle_deg);
    v("max_plane_distance_m", max_plane_distance);
    v("max_gap_m", max_gap);
    v("average_planes", average_planes);
    v("min_wall_length_m", min_wall_length);
    v("min_wall_observations", min_wall_observations);
  }
  /// Throws ConfigError naming the field ("walls.association.<field>").
  void validate() const;
};

class WallMap {
 public:
  struct Association {
    /// Index into the observation vector given to associate().
    int observation_index;
    uint32_t landmark_id;
    /// True when the observation created the landmark.
    bool created;
  };

  /// Validates the configuration (throws ConfigError).
  explicit WallMap(const WallAssociationConfig& config = {});

  /// Associates every observation (base frame) with a landmark, creating landmarks as needed,
  /// in observation order. Returns one entry per observation.
  std::vector<Association> associate(const std::vector<WallSegment>& observations_in_base,
                                     const Pose3& T_map_base);

  /// Folds landmarks that describe the same wall (same side, same plane within the association
  /// gates, overlapping or adjacent extents) into the one with more observations (ties: lower id).
  /// Returns (removed_id, kept_id) pairs; kept_id always names a landmark that still exists.
  std::vector<std::pair<uint32_t, uint32_t>> mergeDuplicates();

  const std::map<uint32_t, WallLandmark>& landmarks() const { return landmarks_; }

  /// Remembers surfaces the sensor saw over (WallExtractionResult::seen_over, base frame): they
  /// are gathered apart from the landmarks, associated among themselves with the same gates.
  void addSeenOver(const std::vector<WallSegment>& observations_in_base, const Pose3& T_map_base);

  /// True when at least half of the landmark's length lies on surfaces seen over: on the same side
  /// with the plane within half the association distance and the mean top within 0.5 m of the
  /// landmark's (a cabinet or a half wall observed from too close to see over it), or facing away
  /// up to 1 m behind it with no other wall's face between (the back of a free-standing cabinet
  /// seen over from the far side). Not a wall. Unknown ids are false.
  bool isSeenOver(uint32_t id) const;

  /// True when the landmark stands up to 1 m in front of a same-facing wall landmark (at least
  /// min_wall_length long, overlapping half its length or more) whose mean top is over 0.5 m
  /// higher: a machine, a shelf or lockers against a wall. The wall was seen above it, so its
  /// top is open: it bounds no room. Unknown ids are false.
  bool standsBeforeATallerWall(uint32_t id) const;

  /// True when the landmark is a wall: at least min_wall_length long, observed at least
  /// min_wall_observations times, not isSeenOver() and not standsBeforeATallerWall().
  bool isWall(uint32_t id) const;

  /// True when nothing marks the landmark as furniture: at least min_wall_length long, not
  /// isSeenOver() and not standsBeforeATallerWall(). isWall() also asks for enough observations;
  /// this does not, so a wall seen from few keyframes yet already anchors (rooms/room_bounds.h).
  /// In a mirror (setLandmarks with wall_ids) a landmark that is no wall although long and
  /// observed enough is furniture.
  bool hasWallShape(uint32_t id) const;

  /// The landmarks that are walls (isWall()).
  std::map<uint32_t, WallLandmark> walls() const;

  /// The surfaces seen over, merged per surface (map frame).
  const std::vector<WallLandmark>& seenOverSurfaces() const { return seen_over_; }

  /// Sets a landmark's plane (after optimisation) and moves its extent onto the new plane. A
  /// normal given with the opposite sign is flipped so the landmark keeps its facing direction.
  /// Unknown ids are ignored.
  void updateLandmarkPlane(uint32_t id, const Eigen::Vector3d& normal, double d);

  const WallAssociationConfig& config() const { return config_; }

  /// Replaces every landmark with `landmarks` (ids kept; ids given later continue after the
  /// largest). A process that does not own the backend mirrors its wall map this way; its
  /// seen-over surfaces are not mirrored, so `wall_ids`, when given, are the landmarks that are
  /// walls in the mirrored map and isWall() answers from them.
  void setLandmarks(std::map<uint32_t, WallLandmark> landmarks,
                    std::optional<std::set<uint32_t>> wall_ids = std::nullopt);

 private:
  /// True when a wall (a landmark at least min_wall_length long, across the line) meets the line
  /// of a and b in the gap between their extents: a partition at a T junction, whose two sides
  /// are two rooms. Such pieces stay two landmarks however narrow the partition.
  bool separatedByAWall(const WallLandmark& a, const WallLandmark& b) const;

  WallAssociationConfig config_;
  std::map<uint32_t, WallLandmark> landmarks_;
  std::vector<WallLandmark> seen_over_;
  std::optional<std::set<uint32_t>> mirrored_walls_;  // setLandmarks' wall_ids
  uint32_t next_id_ = 0;
};

/// The walls of a scene graph (the backend's optimised landmarks) as a WallMap with the same
/// landmark ids, so that rooms extracted from it name the backend's walls. `observations` gives
/// the observation count of each wall (1 when absent); the inlier weight is unknown (0). isWall()
/// is the graph's WallNode::is_wall.
WallMap wallMapFromSceneGraph(const SceneGraph& graph,
                              const std::map<uint32_t, uint32_t>& observations = {},
                              const WallAssociationConfig& config = {});

}  // namespace tacs
