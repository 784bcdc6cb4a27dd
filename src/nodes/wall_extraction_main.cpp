// wall_extraction node (see include/tacs_graphs/ros/wall_extraction_node.h).
#include "tacs_graphs/ros/node_runner.h"
#include "tacs_graphs/ros/wall_extraction_node.h"

int main(int argc, char** argv) {
  tacs::NodeHooks<tacs::WallExtractionNode> hooks;
  hooks.on_stop = [](tacs::WallExtractionNode& node) {
    ROS_INFO_STREAM("wall_extraction: " << node.keyframesProcessed() << " keyframes processed, "
                                        << node.warnings() << " warnings");
  };
  return tacs::runNode(argc, argv, "wall_extraction", hooks);
}
