// room_segmentation node (see include/tacs_graphs/ros/room_segmentation_node.h).
#include "tacs_graphs/ros/node_runner.h"
#include "tacs_graphs/ros/room_segmentation_node.h"

int main(int argc, char** argv) {
  tacs::NodeHooks<tacs::RoomSegmentationNode> hooks;
  hooks.on_stop = [](tacs::RoomSegmentationNode& node) { node.shutdown(); };
  return tacs::runNode(argc, argv, "room_segmentation", hooks);
}
