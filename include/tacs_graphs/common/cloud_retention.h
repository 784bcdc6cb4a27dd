// Which keyframe clouds stay in memory over a long run. A robot that drives the same building for
// hours adds keyframes at the same places on every pass; their poses are cheap, their clouds are
// not (a few hundred kB each). Once a place holds enough clouds from earlier passes, the clouds of
// later keyframes there are dropped, so memory follows the mapped area rather than the run time.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace tacs {

struct CloudRetentionConfig {
  // A keyframe's cloud is dropped once the keyframe is min_age_keyframes old and at least
  // max_clouds_per_place older kept clouds lie within place_radius_m of it. With keyframes every
  // 0.5 m, 8 clouds within 1 m are about two passes. 0 keeps every cloud.
  double place_radius_m = 1.0;  // [m]
  int max_clouds_per_place = 8;
  int min_age_keyframes = 20;  // [keyframes] younger clouds serve as loop queries and stay

  template <class V>
  void visit(V& v) {
    v("place_radius_m", place_radius_m);
    v("max_clouds_per_place", max_clouds_per_place);
    v("min_age_keyframes", min_age_keyframes);
  }
  /// `section` names the configuration path in errors, e.g. "map_export.cloud_retention.".
  void validate(const std::string& section) const;
};

class CloudRetention {
 public:
  /// Current position estimate of a keyframe (the map moves with every optimisation).
  using PositionOf = std::function<Eigen::Vector3d(uint32_t)>;

  explicit CloudRetention(const CloudRetentionConfig& config);

  /// Registers a new keyframe (ids in arrival order). Returns the keyframe whose cloud became
  /// redundant with this arrival, if any; the caller frees that cloud.
  std::optional<uint32_t> add(uint32_t id, const PositionOf& position_of);

  size_t keptCount() const { return young_.size() + kept_old_.size(); }
  size_t droppedCount() const { return dropped_; }

 private:
  CloudRetentionConfig config_;
  std::deque<uint32_t> young_;      // kept, not yet min_age_keyframes old
  std::vector<uint32_t> kept_old_;  // kept and old: the places' clouds
  size_t dropped_ = 0;
};

}  // namespace tacs
