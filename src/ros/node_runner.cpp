#include "tacs_graphs/ros/node_runner.h"

#include <ros/callback_queue.h>
#include <ros/ros.h>

#include <atomic>
#include <csignal>

namespace tacs {
namespace {

std::atomic<bool> g_stop_requested{false};

void onStopSignal(int) { g_stop_requested = true; }

}  // namespace

void installStopHandler() {
  std::signal(SIGINT, onStopSignal);
  std::signal(SIGTERM, onStopSignal);
}

void spinUntilStopped(const std::function<void()>& after_callbacks) {
  while (ros::ok() && !g_stop_requested) {
    ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.1));
    if (after_callbacks) after_callbacks();
  }
}

}  // namespace tacs
