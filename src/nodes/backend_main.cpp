// backend node (see include/tacs_graphs/ros/backend_node.h).
#include "tacs_graphs/ros/backend_node.h"
#include "tacs_graphs/ros/node_runner.h"

int main(int argc, char** argv) {
  tacs::NodeHooks<tacs::BackendNode> hooks;
  hooks.after_callbacks = [](tacs::BackendNode& node) { node.publishIfChanged(); };
  hooks.on_stop = [](tacs::BackendNode& node) { node.shutdown(); };
  return tacs::runNode(argc, argv, "backend", hooks);
}
