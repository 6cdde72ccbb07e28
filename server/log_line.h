// One line of the server's log, written so that it can never take a call with it.
#pragma once

#include <mutex>
#include <ostream>
#include <sstream>
#include <string>

namespace snooker::server {

/// Writes the line `build` makes (it is given a stream set to fixed notation with
/// three decimals) to `log`, under `mu`. Never throws: a line that cannot be built, or
/// that the stream refuses (a full disk, a closed descriptor, a stream set to throw),
/// is lost and false returned, and the stream is cleared so that the next line tries
/// again.
template <typename Build>
bool WriteLogLine(std::ostream& log, std::mutex& mu, Build&& build) noexcept {
  try {
    std::ostringstream line;
    line.precision(3);
    line << std::fixed;
    build(line);
    const std::string text = line.str();
    std::lock_guard<std::mutex> lock(mu);
    bool written = false;
    try {
      log << text << std::flush;
      written = static_cast<bool>(log);
    } catch (...) {
    }
    if (!written) log.clear();  // the state is good after it, so it cannot throw
    return written;
  } catch (...) {
    return false;
  }
}

}  // namespace snooker::server
