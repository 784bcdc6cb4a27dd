#include "tacs_graphs/common/keyframe_retention.h"

#include "tacs_graphs/common/config.h"

namespace tacs {

void KeyframeRetentionConfig::validate(const std::string& section) const {
  requireConfig(place_radius_m > 0.0, section + "place_radius_m", "must be > 0");
  requireConfig(max_keyframes_per_place >= 0, section + "max_keyframes_per_place",
                "must be >= 0 (0 keeps everything)");
  requireConfig(min_age_keyframes >= 0, section + "min_age_keyframes", "must be >= 0");
}

KeyframeRetention::KeyframeRetention(const KeyframeRetentionConfig& config) : config_(config) {}

std::optional<uint32_t> KeyframeRetention::add(uint32_t id, const PositionOf& position_of) {
  young_.push_back(id);
  if (young_.size() <= static_cast<size_t>(config_.min_age_keyframes)) return std::nullopt;
  const uint32_t aged = young_.front();
  young_.pop_front();
  if (config_.max_keyframes_per_place == 0) {
    kept_old_.push_back(aged);
    return std::nullopt;
  }
  // Linear in the kept keyframes, which the rule itself bounds by the mapped area (a few thousand
  // at most): microseconds per keyframe.
  const Eigen::Vector3d p = position_of(aged);
  const double radius_sq = config_.place_radius_m * config_.place_radius_m;
  int nearby = 0;
  for (uint32_t other : kept_old_) {
    if ((position_of(other) - p).squaredNorm() <= radius_sq &&
        ++nearby >= config_.max_keyframes_per_place) {
      return aged;
    }
  }
  kept_old_.push_back(aged);
  return std::nullopt;
}

}  // namespace tacs
