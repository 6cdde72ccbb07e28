#include "cli/write_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "server/read_file.h"

namespace snooker::cli {
namespace {

// The write itself: false with the system's reason in `why`.
bool WriteThrough(const std::string& path, const std::string& text, std::string* why) {
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    *why = std::strerror(errno);
    return false;
  }
  if (!server::WriteAll(fd, text, why)) {
    close(fd);
    return false;
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
