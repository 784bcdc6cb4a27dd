// room_segmentation node (see include/tacs_graphs/ros/room_segmentation_node.h).
#include <ros/ros.h>

#include "tacs_graphs/common/config.h"
#include "tacs_graphs/common/heap.h"
#include "tacs_graphs/ros/node_runner.h"
#include "tacs_graphs/ros/room_segmentation_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "room_segmentation", ros::init_options::NoSigintHandler);
  tacs::installStopHandler();
  tacs::retainFreedHeapMemory();
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  try {
    tacs::RoomSegmentationNode node(nh, pnh);
    tacs::spinUntilStopped();
    node.shutdown();
  } catch (const tacs::ConfigError& e) {
    ROS_FATAL_STREAM("room_segmentation: bad configuration: " << e.what());
    return 1;
  }
  return 0;
}
