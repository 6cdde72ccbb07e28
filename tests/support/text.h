// Text checks the suites share.
#pragma once

#include <string>

namespace snooker {

/// Whether `text` contains `part` (an error message naming a field, a log line ...).
inline bool Mentions(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace snooker
