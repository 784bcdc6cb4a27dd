#include "tacs_graphs/common/message_reason.h"

#include <cctype>

namespace tacs {

std::string messageReason(const std::string& text) {
  const auto digit = [&text](size_t i) {
    return i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])) != 0;
  };
  std::string key;
  key.reserve(text.size());
  for (size_t i = 0; i < text.size(); ++i) {
    if (!digit(i)) {
      key += text[i];
      continue;
    }
    // A minus sign (not a hyphen: "OS0-128") belongs to the number.
    const size_t n = key.size();
    if (n > 0 && key[n - 1] == '-' && (n == 1 || key[n - 2] == ' ' || key[n - 2] == '(')) {
      key.pop_back();
    }
    key += '#';
    while (digit(i + 1) || (text[i + 1] == '.' && digit(i + 2))) ++i;
  }
  return key;
}

}  // namespace tacs
