// traversability node (see include/tacs_graphs/ros/traversability_node.h).
#include "tacs_graphs/ros/node_runner.h"
#include "tacs_graphs/ros/traversability_node.h"

int main(int argc, char** argv) {
  tacs::NodeHooks<tacs::TraversabilityNode> hooks;
  hooks.on_stop = [](tacs::TraversabilityNode& node) {
    ROS_INFO_STREAM("traversability: " << node.keyframesProcessed() << " keyframes processed, "
                                       << node.warnings() << " warnings");
  };
  return tacs::runNode(argc, argv, "traversability", hooks);
}
