#include "tacs_graphs/ros/keyframe_input.h"

#include "tacs_graphs/ros/cloud_conversion.h"
#include "tacs_graphs/ros/message_conversion.h"

namespace tacs {

KeyframeInput fromKeyframeMsg(const tacs_graphs::Keyframe& msg) {
  KeyframeInput in;
  in.id = msg.id;
  in.stamp = msg.header.stamp.toSec();
  in.T_odom_base = fromPoseMsg(msg.odom_pose);
  in.information = fromMatrixArray(msg.odom_information);
  in.sensor_in_base = fromPoint(msg.sensor_origin);
  if (!in.T_odom_base.matrix().allFinite()) {
    in.error = "non-finite keyframe pose";
    return in;
  }
  if (!in.information.allFinite()) {
    in.error = "non-finite keyframe information";
    return in;
  }
  if (!in.sensor_in_base.allFinite()) {
    in.error = "non-finite keyframe sensor origin";
    return in;
  }
  in.cloud.reset(new PointCloud);
  const CloudConversionResult conv = fromRosCloud(msg.cloud, in.cloud.get());
  if (!conv.ok) {
    in.error = "keyframe cloud: " + conv.error;
    return in;
  }
  in.ok = true;
  return in;
}

}  // namespace tacs
