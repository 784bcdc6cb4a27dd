// The main loop of the nodes. roscpp's own SIGINT handler shuts ROS down before main() regains
// control, which also silences logging; the nodes install this handler instead (ros::init with
// ros::init_options::NoSigintHandler), so that their shutdown work (the backend's final save, the
// summaries) still runs with ROS up and is logged.
#pragma once

#include <functional>

namespace tacs {

/// Installs a SIGINT/SIGTERM handler that only sets a flag.
void installStopHandler();

/// Processes callbacks until SIGINT/SIGTERM or ros::shutdown(); `after_callbacks`, if given, runs
/// after every batch of callbacks that were waiting together.
void spinUntilStopped(const std::function<void()>& after_callbacks = {});

}  // namespace tacs
