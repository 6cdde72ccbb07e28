// Text checks the suites share.
#pragma once

#include <cstddef>
#include <string>

namespace snooker {

/// Whether `text` contains `part` (an error message naming a field, a log line ...).
inline bool Mentions(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// How many times `part` (not empty) stands in `text`, without overlaps.
inline int Occurrences(const std::string& text, const std::string& part) {
  int n = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + part.size())) ++n;
  return n;
}

}  // namespace snooker
