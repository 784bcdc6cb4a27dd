// wall_extraction node (see include/tacs_graphs/ros/wall_extraction_node.h).
#include <ros/ros.h>

#include "tacs_graphs/common/config.h"
#include "tacs_graphs/common/heap.h"
#include "tacs_graphs/ros/node_runner.h"
#include "tacs_graphs/ros/wall_extraction_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "wall_extraction", ros::init_options::NoSigintHandler);
  tacs::installStopHandler();
  tacs::retainFreedHeapMemory();
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  try {
    tacs::WallExtractionNode node(nh, pnh);
    tacs::spinUntilStopped();
    ROS_INFO_STREAM("wall_extraction: " << node.keyframesProcessed() << " keyframes processed, "
                                        << node.warnings() << " warnings");
  } catch (const tacs::ConfigError& e) {
    ROS_FATAL_STREAM("wall_extraction: bad configuration: " << e.what());
    return 1;
  }
  return 0;
}
