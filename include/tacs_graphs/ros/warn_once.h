// Logs each distinct reason for dropping a message once, then counts repeats silently: a node
// fed a stream of bad messages keeps a readable log and keeps running.
#pragma once

#include <map>
#include <string>

namespace tacs {

class WarnOnce {
 public:
  /// Logs "<what>: <reason>" on the first occurrence of `reason`; counts every occurrence.
  void warn(const std::string& what, const std::string& reason);
  /// As warn(), counting by `reason` but logging `detail` (the message with its numbers).
  void warn(const std::string& what, const std::string& reason, const std::string& detail);
  /// Counting key of a message with numbers: messageReason() (common/message_reason.h).
  static std::string reasonKey(const std::string& detail);
  size_t count(const std::string& reason) const;
  size_t total() const { return total_; }

 private:
  std::map<std::string, size_t> counts_;
  size_t total_ = 0;
};

}  // namespace tacs
