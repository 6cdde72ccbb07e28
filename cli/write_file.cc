#include "cli/write_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace snooker::cli {
namespace {

// The write itself: false with the system's reason in `why`.
bool WriteThrough(const std::string& path, const std::string& text, std::string* why) {
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    *why = std::strerror(errno);
    return false;
  }
  std::size_t done = 0;
  int interrupted = 0;
  // Each turn writes at least one byte, is one of at most 100 interruptions in a row,
  // or ends the loop.
  while (done < text.size()) {
    const ssize_t n = write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR && ++interrupted < 100) continue;
    interrupted = 0;
    if (n <= 0) {
      *why = n < 0 ? std::strerror(errno) : "the device took no more bytes";
      close(fd);
      return false;
    }
    done += static_cast<std::size_t>(n);
  }
  if (close(fd) != 0) {  // a file system that reports a failed write only here (NFS)
    *why = std::strerror(errno);
    return false;
  }
  return true;
}

}  // namespace

bool WriteOutputFile(const std::string& path, const std::string& text, const std::string& command,
                     std::ostream& err) {
  std::string why;
  if (WriteThrough(path, text, &why)) return true;
  err << command << ": cannot write '" << path << "': " << why << "\n";
  return false;
}

}  // namespace snooker::cli
