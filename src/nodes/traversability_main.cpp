// traversability node (see include/tacs_graphs/ros/traversability_node.h).
#include <ros/ros.h>

#include "tacs_graphs/common/config.h"
#include "tacs_graphs/common/heap.h"
#include "tacs_graphs/ros/node_runner.h"
#include "tacs_graphs/ros/traversability_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "traversability", ros::init_options::NoSigintHandler);
  tacs::installStopHandler();
  tacs::retainFreedHeapMemory();
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  try {
    tacs::TraversabilityNode node(nh, pnh);
    tacs::spinUntilStopped();
    ROS_INFO_STREAM("traversability: " << node.keyframesProcessed() << " keyframes processed, "
                                       << node.warnings() << " warnings");
  } catch (const tacs::ConfigError& e) {
    ROS_FATAL_STREAM("traversability: bad configuration: " << e.what());
    return 1;
  }
  return 0;
}
