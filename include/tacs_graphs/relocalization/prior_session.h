// A session run against a prior map (docs/DESIGN.md "Prior maps"). Until it is placed, the
// session maps in its own frame and tries each room it segments (RoomRelocalizer). Once placed,
// every later room refines the place (the session's whole map registered to the prior's), and at
// the end the session's rooms are paired with the prior's. Then:
// - localize-only: the prior graph is kept as it is, byte for byte; the session is reported in the
//   prior's frame beside it;
// - merge: the session's keyframes, walls and rooms join the prior graph, a re-observed room or
//   wall under its prior id, a new one under a new id.
// ROS-free: tacs_offline calls it after every scan that brought rooms; localization.json is the
// record of what happened.
#pragma once

#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "tacs_graphs/backend/map_export.h"
#include "tacs_graphs/common/config.h"
#include "tacs_graphs/relocalization/room_relocalizer.h"

namespace tacs {

enum class PriorMode { kLocalizeOnly, kMerge };
template <>
struct EnumNames<PriorMode> {
  static constexpr std::array<std::pair<PriorMode, const char*>, 2> kNames{
      {{PriorMode::kLocalizeOnly, "localize_only"}, {PriorMode::kMerge, "merge"}}};
};

/// The first placement of the session.
struct FirstLocalization {
  double stamp = 0.0;       // of the scan whose room placed the session
  double distance_m = 0.0;  // driven by then
  RelocalizationAttempt attempt;
};

class PriorSession {
 public:
  /// Throws ConfigError on a bad configuration.
  PriorSession(PriorMap prior, PriorMode mode, const RelocalizationConfig& config);

  /// After a scan: tries the rooms not tried yet (or grown by half since their last try) while
  /// unplaced, and the whole map after relocalization.retry_distance_m without an attempt;
  /// refines the place when a new room appears once placed. `distance_m`: driven so far.
  void update(const SceneGraph& session, const KeyframeClouds& clouds, double stamp,
              double distance_m);
  /// At the end of the run: one more try (or refinement) and the room pairs.
  void finish(const SceneGraph& session, const KeyframeClouds& clouds, double stamp,
              double distance_m);

  bool localized() const { return first_.has_value(); }
  /// Unplaced, and far enough since the last attempt for a whole-map one: update() would try.
  bool wantsMapAttempt(double distance_m) const;
  /// The session's map frame in the prior's (identity while unplaced).
  const Pose3& T_prior_session() const { return T_prior_session_; }
  /// Session room id -> prior room id (once placed; final after finish()).
  const std::map<uint32_t, uint32_t>& roomPairs() const { return room_pairs_; }
  PriorMode mode() const { return mode_; }
  const PriorMap& prior() const { return relocalizer_->prior(); }

  /// The graph to save: the prior's (localize-only), or the prior's with the session merged in.
  /// Unplaced: the session's own.
  SceneGraph outputGraph(const SceneGraph& session) const;
  /// localization.json: status (localized | not_localized), mode, prior, the first localization
  /// (stamp, driven distance, rooms, scores), T_prior_session, room_pairs, attempts (and each
  /// one's rooms, scores and result in attempt_log), hypotheses verified and rejected.
  nlohmann::json localizationJson() const;
  /// Writes DIR/localization.json and, once placed, DIR/session_graph.json (the session's graph
  /// in the prior's frame) and DIR/scene_graph.json: the prior's file byte for byte
  /// (localize-only) or the merged graph. Throws std::runtime_error naming the file.
  void writeFiles(const std::string& dir, const SceneGraph& session) const;
  /// Once placed, writes DIR as a prior map for a later run, in the prior's frame: writeFiles()
  /// plus DIR/map.pcd, the prior's points joined by `session_map` (the session's map, in its own
  /// frame) moved into the prior's on a `voxel_m` grid, or the prior's points alone with
  /// localize-only. The backend node's save, whose own folder stays in the session's frame.
  /// Returns false (and writes nothing) while unplaced; throws std::runtime_error naming the file.
  bool writePriorFrameMap(const std::string& dir, const SceneGraph& session,
                          const PointCloud& session_map, double voxel_m) const;

 private:
  PointCloud sessionMap(const SceneGraph& session, const KeyframeClouds& clouds) const;
  void tryRooms(const SceneGraph& session, const KeyframeClouds& clouds, double stamp,
                double distance_m);
  void tryMap(const SceneGraph& session, const KeyframeClouds& clouds, double stamp,
              double distance_m);
  /// Counts an attempt into localization.json; true when it placed the session.
  bool book(const RelocalizationAttempt& attempt, double stamp, double distance_m);
  /// Registers the session's whole map to the prior's from the current place; kept when it fits.
  void refinePlace(const SceneGraph& session, const KeyframeClouds& clouds);

  std::unique_ptr<PriorMap> prior_;
  PriorMode mode_;
  std::unique_ptr<RoomRelocalizer> relocalizer_;
  std::map<uint32_t, size_t> tried_;  // room id -> free-space nodes at its last try
  std::optional<FirstLocalization> first_;
  Pose3 T_prior_session_ = Pose3::Identity();
  double last_refined_score_ = 0.0;
  double last_attempt_m_ = 0.0;  // driven distance at the last attempt
  std::map<uint32_t, uint32_t> room_pairs_;
  nlohmann::json log_ = nlohmann::json::array();  // one entry per attempt
  int attempts_ = 0, hypotheses_ = 0, rejected_ = 0, refinements_ = 0;
  double time_ms_ = 0.0;
};

/// Two walls (or two non-wall planes) on one plane: normals within max_angle_deg, offsets within
/// max_offset_m, their ends overlapping along the first one (0.5 m of slack). The merge takes a
/// session wall for a prior one at 10 deg and 0.3 m.
bool onOnePlane(const WallNode& a, const WallNode& b, double max_angle_deg, double max_offset_m);

/// The session's graph, placed by T_prior_session, merged into the prior's: a session room paired
/// with a prior room (room_pairs) and a session wall on a prior wall's plane (normals within
/// 10 deg, offsets within 0.3 m, overlapping ends) keep the prior's id; every other node and the
/// session's keyframes and loops get new ids above the prior's.
SceneGraph mergeSceneGraphs(const SceneGraph& prior, const SceneGraph& session,
                            const Pose3& T_prior_session,
                            const std::map<uint32_t, uint32_t>& room_pairs);

}  // namespace tacs
