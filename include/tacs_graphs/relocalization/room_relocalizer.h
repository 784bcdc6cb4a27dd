// Relocalization by rooms (docs/DESIGN.md "Prior maps"). A room the session segmented is matched
// against the prior's rooms by its shape: the extents of its free space along its wall axes. Each
// shape match gives up to four place hypotheses (the yaw between the two rooms' axes, modulo the
// room's symmetry). Rooms are cut where the robot entered and left them, so a second source of
// hypotheses does not depend on the cut: the session's wall points slid over the prior's from
// above, at the four yaws that align the maps' wall axes. Each hypothesis is verified as CoSG-LCD
// verifies a loop (paper Sec. III-D): GICP of the session's map against the prior's from the
// hypothesis, wide gate to narrow, scored by the share of the session's wall-like points within the
// prior's reach that land on its surfaces (floors and ceilings fit under any planar shift, so they
// are not scored).
// The best hypothesis places the session when it scores min_score and every distinct hypothesis
// leaves clearly more points off the prior's surfaces (min_misfit_ratio, min_extra_misfits): a
// symmetric room, or two rooms alike, wait for the next room, whose map then holds more of the
// building.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tacs_graphs/common/config.h"
#include "tacs_graphs/odometry/gicp.h"
#include "tacs_graphs/relocalization/prior_map.h"

namespace tacs {

struct RelocalizationConfig {
  // A session room's extents match a prior room's within max(extent_tolerance_m, ratio * extent).
  double extent_tolerance_m = 1.0;       // [m]
  double extent_tolerance_ratio = 0.25;  // [-]
  double cloud_voxel_m = 0.2;            // [m] both maps are registered at this voxel size
  int max_session_points = 40000;        // the session's map is thinned to this many points
  double coarse_gate_m = 1.5;            // [m] GICP correspondence gate of the first stage
  double fine_gate_m = 0.3;              // [m] ... of the last stage (the middle one halfway)
  double fit_distance_m = 0.1;           // [m] a wall point this close to the plane of
  double fit_radius_m = 0.5;             // [m] ... a prior point this near fits
  double overlap_radius_m = 1.0;         // [m] farther than this from any: not scored
  double min_overlap = 0.5;              // [-] the scored points count as at least this share
  double max_normal_z = 0.5;             // [-] |normal z| above this: horizontal, not scored
  double min_score = 0.85;               // [-] share of wall points that fit, to place the session
  // ... and every distinct place must leave min_misfit_ratio times as many wall points off the
  // prior's surfaces (the best's share counted as at least misfit_floor: sensor noise), and at
  // least min_extra_misfits more. A ring of alike corridors differs only by a few benches and
  // doors: 0.1 % against 1 % of the points.
  double min_misfit_ratio = 3.0;     // [-]
  double misfit_floor = 0.002;       // [-]
  int min_extra_misfits = 100;       // [-] wall points
  double distinct_distance_m = 1.0;  // [m] hypotheses farther apart than this, or
  double distinct_angle_deg = 10.0;  // [deg] turned more than this, are distinct places
  int min_wall_points = 300;         // [-] fewer scored points in the session: no attempt
  double room_pair_overlap = 0.5;    // [-] share of a room's free space inside a prior room
  double search_cell_m = 0.5;        // [m] cell of the translation search over wall points
  int search_peaks_per_yaw = 3;      // [-] best shifts of each of the four yaws verified
  double retry_distance_m = 10.0;    // [m] unplaced and no room tried for this long: whole-map
                                     // attempt (a session that segments no room); 0: rooms only

  template <class V>
  void visit(V& v) {
    v("extent_tolerance_m", extent_tolerance_m);
    v("extent_tolerance_ratio", extent_tolerance_ratio);
    v("cloud_voxel_m", cloud_voxel_m);
    v("max_session_points", max_session_points);
    v("coarse_gate_m", coarse_gate_m);
    v("fine_gate_m", fine_gate_m);
    v("fit_distance_m", fit_distance_m);
    v("fit_radius_m", fit_radius_m);
    v("overlap_radius_m", overlap_radius_m);
    v("min_overlap", min_overlap);
    v("max_normal_z", max_normal_z);
    v("min_score", min_score);
    v("min_misfit_ratio", min_misfit_ratio);
    v("misfit_floor", misfit_floor);
    v("min_extra_misfits", min_extra_misfits);
    v("distinct_distance_m", distinct_distance_m);
    v("distinct_angle_deg", distinct_angle_deg);
    v("min_wall_points", min_wall_points);
    v("room_pair_overlap", room_pair_overlap);
    v("search_cell_m", search_cell_m);
    v("search_peaks_per_yaw", search_peaks_per_yaw);
    v("retry_distance_m", retry_distance_m);
  }
  void validate() const;
};

/// A room's footprint: its centre, the yaw of its wall axes (modulo 90 deg) and the extents of
/// its free space along them. ok is false for a room without free space.
struct RoomShape {
  bool ok = false;
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double yaw = 0.0;  // [rad] in [0, pi/2)
  Eigen::Vector2d extent = Eigen::Vector2d::Zero();
};
RoomShape roomShape(const RoomNode& room, const SceneGraph& graph);

/// A place for the session in the prior's map frame.
struct PlaceHypothesis {
  uint32_t prior_room = 0;
  Pose3 T_prior_session = Pose3::Identity();
  double score = 0.0;  // share of the session's wall points that fit the prior
};

struct RelocalizationAttempt {
  std::optional<uint32_t> session_room;  // none: a whole-map attempt (tryMap)
  bool localized = false;
  PlaceHypothesis best;
  double runner_up_score = 0.0;  // best hypothesis at a distinct place (0: none)
  int hypotheses = 0;            // verified by registration
  int rejected = 0;              // verified and not accepted
  size_t wall_points = 0;        // scored points of the session's map
  std::string reason;            // why the session was not placed
  double time_ms = 0.0;
};

class RoomRelocalizer {
 public:
  /// Prepares the prior's map for registration once. Throws ConfigError.
  RoomRelocalizer(const PriorMap& prior, const RelocalizationConfig& config);
  ~RoomRelocalizer();

  /// Tries to place the session by its room `room_id`. `session_points`: the session's map in its
  /// own map frame.
  RelocalizationAttempt tryRoom(const SceneGraph& session, const PointCloud& session_points,
                                uint32_t room_id) const;
  /// Tries to place the session without a room (a session that has segmented none yet): the
  /// wall search's hypotheses only. `where`: a session map point (the robot) whose prior room
  /// names the place.
  RelocalizationAttempt tryMap(const PointCloud& session_points,
                               const Eigen::Vector3d& where) const;
  /// Registers the session's map to the prior's from a known place (middle and narrow gates).
  PlaceHypothesis refine(const PointCloud& session_points, const Pose3& T_prior_session) const;

  const PriorMap& prior() const { return prior_; }
  const RelocalizationConfig& config() const { return config_; }

 private:
  struct SessionCloud;
  struct WallGrid;
  SessionCloud prepare(const PointCloud& session_points) const;
  /// Places of the session's map found by sliding its wall points over the prior's, at the four
  /// yaws that align the two maps' wall axes.
  std::vector<Pose3> searchTranslations(const SessionCloud& session) const;
  std::vector<double> gates() const;  // GICP correspondence gates of a hypothesis, wide to narrow
  /// Prior rooms shaped as the session's room, at the yaws that keep its extents.
  std::vector<PlaceHypothesis> shapeHypotheses(const SessionCloud& cloud,
                                               const RoomShape& shape) const;
  /// Adds the wall search's hypotheses, verifies them all and accepts the best or says why not.
  RelocalizationAttempt decide(const SessionCloud& cloud, std::vector<PlaceHypothesis> verified,
                               const Eigen::Vector3d& anchor, RelocalizationAttempt attempt) const;
  /// The prior room whose free space lies nearest to a map point.
  uint32_t priorRoomAt(const Eigen::Vector3d& p) const;
  /// GICP from `guess` through the given gates, then the score at the result.
  PlaceHypothesis verify(const SessionCloud& session, const Pose3& guess,
                         const std::vector<double>& gates) const;
  double score(const SessionCloud& session, const Pose3& T_prior_session) const;
  bool distinct(const Pose3& a, const Pose3& b) const;

  const PriorMap& prior_;
  RelocalizationConfig config_;
  GicpCloud::ConstPtr prior_cloud_;
  std::map<uint32_t, RoomShape> prior_shapes_;
  double prior_yaw_ = 0.0;  // the prior's wall axes, modulo 90 deg
  std::unique_ptr<WallGrid> prior_grid_;
};

/// Session rooms paired with prior rooms, the session placed by T_prior_session: a session room
/// takes the prior room holding at least `min_overlap` of its free space (the most, when several).
std::map<uint32_t, uint32_t> pairRooms(const SceneGraph& session, const SceneGraph& prior,
                                       const Pose3& T_prior_session, double min_overlap);

}  // namespace tacs
