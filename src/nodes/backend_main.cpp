// backend node (see include/tacs_graphs/ros/backend_node.h).
#include <ros/ros.h>

#include "tacs_graphs/common/config.h"
#include "tacs_graphs/common/heap.h"
#include "tacs_graphs/ros/backend_node.h"
#include "tacs_graphs/ros/node_runner.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "backend", ros::init_options::NoSigintHandler);
  tacs::installStopHandler();
  tacs::retainFreedHeapMemory();
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  try {
    tacs::BackendNode node(nh, pnh);
    tacs::spinUntilStopped([&node] { node.publishIfChanged(); });
    node.shutdown();
  } catch (const tacs::ConfigError& e) {
    ROS_FATAL_STREAM("backend: bad configuration: " << e.what());
    return 1;
  }
  return 0;
}
