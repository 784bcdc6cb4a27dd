#include "tacs_graphs/ros/warn_once.h"

#include <ros/console.h>

namespace tacs {

void WarnOnce::warn(const std::string& what, const std::string& reason) {
  ++total_;
  if (counts_[reason]++ == 0) {
    ROS_WARN_STREAM(what << ": " << reason << " (further messages for this reason are counted, "
                                             "not logged)");
  }
}

size_t WarnOnce::count(const std::string& reason) const {
  const auto it = counts_.find(reason);
  return it == counts_.end() ? 0 : it->second;
}

}  // namespace tacs
