// gicp_odometry: LiDAR odometry node (see include/tacs_graphs/ros/gicp_odometry_node.h).
#include <ros/ros.h>

#include <exception>

#include "tacs_graphs/common/config.h"
#include "tacs_graphs/common/heap.h"
#include "tacs_graphs/ros/gicp_odometry_node.h"
#include "tacs_graphs/ros/node_runner.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "gicp_odometry", ros::init_options::NoSigintHandler);
  tacs::installStopHandler();
  tacs::retainFreedHeapMemory();
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  try {
    tacs::GicpOdometryNode node(nh, pnh);
    tacs::spinUntilStopped();
    ROS_INFO_STREAM("gicp_odometry: " << node.scansProcessed() << " scans processed, "
                                      << node.scansDropped() << " dropped (bad input), "
                                      << node.scansMissing()
                                      << " missing between received scans (full queue or gaps)");
  } catch (const tacs::ConfigError& e) {
    ROS_FATAL_STREAM("gicp_odometry: bad configuration: " << e.what());
    return 1;
  } catch (const std::exception& e) {  // e.g. an unreadable ~poses_file
    ROS_FATAL_STREAM("gicp_odometry: " << e.what());
    return 1;
  }
  return 0;
}
