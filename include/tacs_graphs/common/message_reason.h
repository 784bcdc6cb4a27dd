// The reason of a warning or error message, for logging each reason once: the message with its
// numbers blanked, so "tilts 12.3 deg" and "tilts 4.0 deg" are one reason and "no x field" and
// "no z field" two. The nodes (WarnOnce) and tacs_offline count by it.
#pragma once

#include <string>

namespace tacs {

/// `text` with every number (digits, a decimal point inside, a leading minus) replaced by '#'.
std::string messageReason(const std::string& text);

}  // namespace tacs
