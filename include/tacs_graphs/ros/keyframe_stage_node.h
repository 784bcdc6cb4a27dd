// What the per-keyframe producers (wall_extraction, traversability) share: /tacs/keyframe in,
// one `Output` message per keyframe out on `topic`, published even when empty (the consumer then
// knows that keyframe is complete). A malformed keyframe is warned about once per reason and
// skipped; a keyframe resent for a node restarted after a crash is not processed again: the last
// ~resend_capacity (100) outputs go out again on its tacs_graphs/Resync (resend_buffer.h).
#pragma once

#include <ros/ros.h>
#include <tacs_graphs/Keyframe.h>
#include <tacs_graphs/Resync.h>

#include <cstdint>
#include <functional>
#include <string>

#include "tacs_graphs/ros/keyframe_input.h"
#include "tacs_graphs/ros/params.h"
#include "tacs_graphs/ros/resend_buffer.h"
#include "tacs_graphs/ros/warn_once.h"

namespace tacs {

template <class Output>
class KeyframeStageNode {
 public:
  /// Turns a checked keyframe into the message to publish.
  using Process = std::function<Output(const KeyframeInput&)>;

  /// `what`: the outputs' name in the resend log ("walls", "graphs").
  KeyframeStageNode(ros::NodeHandle& nh, ros::NodeHandle& pnh, const std::string& topic,
                    const std::string& what, Process process)
      : process_(std::move(process)),
        sent_(static_cast<size_t>(boundedParam(pnh, "resend_capacity", 100, 0, true)), what) {
    pub_ = nh.advertise<Output>(topic, 100);
    keyframe_sub_ = nh.subscribe("/tacs/keyframe", 1000, &KeyframeStageNode::keyframeCallback, this,
                                 ros::TransportHints().tcpNoDelay());
    resync_sub_ = nh.subscribe("/tacs/resync", 10, &KeyframeStageNode::resyncCallback, this);
  }

  size_t keyframesProcessed() const { return processed_; }
  /// Keyframes skipped or processed with a warning.
  size_t warnings() const { return warnings_.total(); }
  WarnOnce& warner() { return warnings_; }

 private:
  void keyframeCallback(const tacs_graphs::Keyframe::ConstPtr& msg) {
    const KeyframeInput kf = fromKeyframeMsg(*msg);
    if (!kf.ok) {
      warnings_.warn("keyframe", WarnOnce::reasonKey(kf.error), kf.error + ", skipped");
      return;
    }
    if (static_cast<int64_t>(kf.id) <= newest_id_) return;  // resent for a restarted node
    newest_id_ = kf.id;
    ++processed_;
    pub_.publish(sent_.keep(kf.id, process_(kf)));
  }

  void resyncCallback(const tacs_graphs::Resync::ConstPtr& msg) { sent_.answer(*msg, pub_); }

  Process process_;
  ResendBuffer<Output> sent_;
  ros::Subscriber keyframe_sub_, resync_sub_;
  ros::Publisher pub_;
  int64_t newest_id_ = -1;
  WarnOnce warnings_;
  size_t processed_ = 0;
};

}  // namespace tacs
