// The last messages a producer (gicp_odometry: keyframes; wall_extraction: walls; traversability:
// graphs) published, by keyframe id, to answer a tacs_graphs/Resync of a node restarted after a
// crash (message_journal.h): what was published while that node was down is sent again.
#pragma once

#include <ros/ros.h>
#include <tacs_graphs/Resync.h>

#include <cstdint>
#include <map>
#include <string>
#include <utility>

namespace tacs {

/// Asks for everything from keyframe `from_keyframe_id` on (a restarted node, after its replay):
/// a latched tacs_graphs/Resync on /tacs/resync; keep the returned publisher alive.
inline ros::Publisher requestResync(ros::NodeHandle& nh, const std::string& requester,
                                    uint32_t from_keyframe_id) {
  tacs_graphs::Resync resync;
  resync.header.stamp = ros::Time::now();
  resync.requester = requester;
  resync.from_keyframe_id = from_keyframe_id;
  ros::Publisher publisher = nh.advertise<tacs_graphs::Resync>("/tacs/resync", 1, /*latch=*/true);
  publisher.publish(resync);
  ROS_WARN_STREAM(requester << ": asked for what was sent from keyframe " << from_keyframe_id
                            << " on");
  return publisher;
}

template <class Message>
class ResendBuffer {
 public:
  /// Keeps the newest `capacity` messages (0: none, resending is off).
  ResendBuffer(size_t capacity, std::string what) : capacity_(capacity), what_(std::move(what)) {}

  /// Takes the message to publish and keeps it: publish the returned pointer (no copy).
  boost::shared_ptr<const Message> keep(uint32_t keyframe_id, Message msg) {
    auto kept = boost::make_shared<const Message>(std::move(msg));
    if (capacity_ == 0) return kept;
    kept_[keyframe_id] = kept;
    while (kept_.size() > capacity_) kept_.erase(kept_.begin());
    return kept;
  }

  bool has(uint32_t keyframe_id) const { return kept_.count(keyframe_id) > 0; }

  /// Publishes again every kept message from `request.from_keyframe_id` on and logs it, with the
  /// ids asked for that are no longer kept.
  void answer(const tacs_graphs::Resync& request, ros::Publisher& publisher) const {
    size_t sent = 0;
    for (auto it = kept_.lower_bound(request.from_keyframe_id); it != kept_.end(); ++it) {
      publisher.publish(it->second);
      ++sent;
    }
    std::string lost;
    if (!kept_.empty() && request.from_keyframe_id < kept_.begin()->first) {
      lost = "; ids " + std::to_string(request.from_keyframe_id) + " to " +
             std::to_string(kept_.begin()->first - 1) + " are no longer kept";
    }
    ROS_WARN_STREAM(request.requester << " restarted: resent " << sent << " " << what_
                                      << " from keyframe " << request.from_keyframe_id << lost);
  }

 private:
  size_t capacity_;
  std::string what_;
  std::map<uint32_t, boost::shared_ptr<const Message>> kept_;
};

}  // namespace tacs
