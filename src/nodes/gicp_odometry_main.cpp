// gicp_odometry: LiDAR odometry node (see include/tacs_graphs/ros/gicp_odometry_node.h).
#include "tacs_graphs/ros/gicp_odometry_node.h"
#include "tacs_graphs/ros/node_runner.h"

int main(int argc, char** argv) {
  tacs::NodeHooks<tacs::GicpOdometryNode> hooks;
  hooks.on_stop = [](tacs::GicpOdometryNode& node) {
    ROS_INFO_STREAM("gicp_odometry: " << node.scansProcessed() << " scans processed, "
                                      << node.scansDropped() << " dropped (bad input), "
                                      << node.scansMissing()
                                      << " missing between received scans (full queue or gaps)");
  };
  return tacs::runNode(argc, argv, "gicp_odometry", hooks);
}
