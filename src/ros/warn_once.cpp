#include "tacs_graphs/ros/warn_once.h"

#include <ros/console.h>

#include "tacs_graphs/common/message_reason.h"

namespace tacs {

void WarnOnce::warn(const std::string& what, const std::string& reason) {
  warn(what, reason, reason);
}

void WarnOnce::warn(const std::string& what, const std::string& reason, const std::string& detail) {
  ++total_;
  if (counts_[reason]++ == 0) {
    ROS_WARN_STREAM(what << ": " << detail
                         << " (further messages for this reason are counted, "
                            "not logged)");
  }
}

std::string WarnOnce::reasonKey(const std::string& detail) { return messageReason(detail); }

size_t WarnOnce::count(const std::string& reason) const {
  const auto it = counts_.find(reason);
  return it == counts_.end() ? 0 : it->second;
}

}  // namespace tacs
