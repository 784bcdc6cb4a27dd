// Which keyframes keep their bulky data (clouds, local traversable graphs) over a long run. A robot
// that drives the same building for hours adds keyframes at the same places on every pass; their
// poses are cheap, their clouds are not (a few hundred kB each). Once a place holds enough
// keyframes' data from earlier passes, the data of later keyframes there is released, so memory
// follows the mapped area rather than the run time.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace tacs {

struct KeyframeRetentionConfig {
  // A keyframe's data is released once the keyframe is min_age_keyframes old and at least
  // max_keyframes_per_place older keyframes that keep theirs lie within place_radius_m of it. With
  // keyframes every 0.5 m, 8 within 1 m are about two passes. 0 keeps everything.
  double place_radius_m = 1.0;  // [m]
  int max_keyframes_per_place = 8;
  int min_age_keyframes = 20;  // [keyframes] the newest keyframes (loop queries) keep theirs

  template <class V>
  void visit(V& v) {
    v("place_radius_m", place_radius_m);
    v("max_keyframes_per_place", max_keyframes_per_place);
    v("min_age_keyframes", min_age_keyframes);
  }
  /// `section` names the configuration path in errors, e.g. "map_export.cloud_retention.".
  void validate(const std::string& section) const;
};

class KeyframeRetention {
 public:
  /// Current position estimate of a keyframe (the map moves with every optimisation).
  using PositionOf = std::function<Eigen::Vector3d(uint32_t)>;

  explicit KeyframeRetention(const KeyframeRetentionConfig& config);

  /// Registers a new keyframe (ids in arrival order). Returns the keyframe whose data became
  /// redundant with this arrival, if any; the caller releases it.
  std::optional<uint32_t> add(uint32_t id, const PositionOf& position_of);

  size_t keptCount() const { return young_.size() + kept_old_.size(); }

 private:
  KeyframeRetentionConfig config_;
  std::deque<uint32_t> young_;      // kept, not yet min_age_keyframes old
  std::vector<uint32_t> kept_old_;  // kept and old: the places' data
};

}  // namespace tacs
