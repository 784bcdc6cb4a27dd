// play_bag: plays a bag into the running suite as fast as the odometry keeps up, without drops
// (see include/tacs_graphs/ros/bag_player.h).
//
//   rosrun tacs_graphs play_bag BAG [--topic CLOUD_TOPIC] [--max-rate X] [--in-flight N]
//                                   [--ack-timeout S] [--wait S]
// The suite runs with use_sim_time (the player publishes /clock from the bag's times).
#include <ros/ros.h>

#include <cstdlib>
#include <iostream>
#include <string>

#include "tacs_graphs/ros/bag_player.h"

namespace {

int usage(const std::string& why) {
  std::cerr << "error: " << why << "\n"
            << "usage: rosrun tacs_graphs play_bag BAG [--topic CLOUD_TOPIC] [--max-rate X]\n"
            << "         [--in-flight N] [--ack-timeout S] [--wait S]\n";
  return 2;
}

bool parseNumber(const std::string& text, double* value) {
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return !text.empty() && end && *end == '\0' && *value >= 0.0;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "play_bag", ros::init_options::AnonymousName);
  tacs::BagPlayerOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--", 0) != 0) {
      if (!options.bag.empty()) return usage("one bag only (" + options.bag + ", " + arg + ")");
      options.bag = arg;
      continue;
    }
    if (i + 1 >= argc) return usage(arg + " needs a value");
    const std::string value = argv[++i];
    double number = 0.0;
    if (arg == "--topic") {
      options.cloud_topic = value;
    } else if (!parseNumber(value, &number)) {
      return usage(arg + " wants a number >= 0, not '" + value + "'");
    } else if (arg == "--max-rate") {
      options.max_rate = number;
    } else if (arg == "--in-flight") {
      options.max_in_flight = static_cast<int>(number);
    } else if (arg == "--ack-timeout") {
      options.ack_timeout_s = number;
    } else if (arg == "--wait") {
      options.wait_for_suite_s = number;
    } else {
      return usage("unknown option " + arg);
    }
  }
  if (options.bag.empty()) return usage("no bag given");
  ros::NodeHandle nh;
  try {
    tacs::BagPlayer player(nh, options);
    std::cout << "play_bag: " << options.bag << ", paced on " << player.cloudTopic() << " by "
              << options.ack_topic << std::endl;
    tacs::BagPlayerResult r;
    std::string error;
    if (!player.play(&r, &error)) {
      std::cerr << "error: " << error << std::endl;
      return 1;
    }
    std::cout << "play_bag: " << r.messages << " messages, " << r.acknowledged << " of " << r.clouds
              << " scans acknowledged (" << r.timed_out << " timed out) in " << r.wall_s
              << " s: " << r.clouds / std::max(r.wall_s, 1e-9) << " scans/s, "
              << r.bag_s / std::max(r.wall_s, 1e-9) << "x the bag's time" << std::endl;
    return r.timed_out == 0 && r.acknowledged == r.clouds ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << std::endl;
    return 1;
  }
}
