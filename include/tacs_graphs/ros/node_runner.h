// The main loop of the nodes. roscpp's own SIGINT handler shuts ROS down before main() regains
// control, which also silences logging; the nodes install this handler instead (ros::init with
// ros::init_options::NoSigintHandler), so that their shutdown work (the backend's final save, the
// summaries) still runs with ROS up and is logged.
#pragma once

#include <ros/ros.h>

#include <exception>
#include <functional>
#include <string>

#include "tacs_graphs/common/config.h"
#include "tacs_graphs/common/process_setup.h"

namespace tacs {

/// Installs a SIGINT/SIGTERM handler that only sets a flag.
void installStopHandler();

/// Processes callbacks until SIGINT/SIGTERM or ros::shutdown(); `after_callbacks`, if given, runs
/// after every batch of callbacks that were waiting together.
void spinUntilStopped(const std::function<void()>& after_callbacks = {});

/// What a node does besides answering its subscriptions.
template <class Node>
struct NodeHooks {
  std::function<void(Node&)> after_callbacks;  ///< after every batch of callbacks
  std::function<void(Node&)> on_stop;          ///< once, after SIGINT/SIGTERM, with ROS still up
};

/// The whole main() of a node: process setup (common/process_setup.h, before ros::init, which
/// strips the remapping arguments from argv), ros::init under `name`, the node built from the
/// global and private handles, the spin, then the hooks. A bad configuration or a failure in the
/// constructor (e.g. an unreadable file parameter) is logged as fatal and exits 1.
template <class Node>
int runNode(int argc, char** argv, const std::string& name, const NodeHooks<Node>& hooks = {}) {
  setUpProcess(argv);
  ros::init(argc, argv, name, ros::init_options::NoSigintHandler);
  installStopHandler();
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  try {
    Node node(nh, pnh);
    std::function<void()> after_callbacks;
    if (hooks.after_callbacks) after_callbacks = [&] { hooks.after_callbacks(node); };
    spinUntilStopped(after_callbacks);
    if (hooks.on_stop) hooks.on_stop(node);
  } catch (const ConfigError& e) {
    ROS_FATAL_STREAM(name << ": bad configuration: " << e.what());
    return 1;
  } catch (const std::exception& e) {
    ROS_FATAL_STREAM(name << ": " << e.what());
    return 1;
  }
  return 0;
}

}  // namespace tacs
