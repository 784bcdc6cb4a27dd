// loop_closure node (see include/tacs_graphs/ros/loop_closure_node.h).
#include "tacs_graphs/ros/loop_closure_node.h"
#include "tacs_graphs/ros/node_runner.h"

int main(int argc, char** argv) {
  tacs::NodeHooks<tacs::LoopClosureNode> hooks;
  hooks.on_stop = [](tacs::LoopClosureNode& node) { node.shutdown(); };
  return tacs::runNode(argc, argv, "loop_closure", hooks);
}
