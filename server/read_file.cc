#include "server/read_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <new>

namespace snooker::server {
namespace {

// Closes a file descriptor when it goes out of scope.
struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) close(fd);
  }
};

const char* NotRegular(mode_t mode) {
  if (S_ISDIR(mode)) return "is a directory";
  if (S_ISFIFO(mode)) return "is a FIFO (named pipe), not a regular file";
  if (S_ISCHR(mode)) return "is a character device, not a regular file";
  if (S_ISBLK(mode)) return "is a block device, not a regular file";
  if (S_ISSOCK(mode)) return "is a socket, not a regular file";
  return "is not a regular file";
}

std::string TooLarge(long long size) {
  return "is " + std::to_string(size) + " bytes; at most " + std::to_string(kMaxInputFileBytes) +
         " (16 MB) are read";
}

}  // namespace

bool ReadInputFile(const std::string& path, std::string* text, std::string* why) {
  // O_NONBLOCK: opening a FIFO without a writer must not wait for one. The checks
  // are on the opened file (fstat), so the path cannot change between check and read.
  Fd f{open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY)};
  if (f.fd < 0) {
    *why = std::strerror(errno);
    return false;
  }
  struct stat st {};
  if (fstat(f.fd, &st) != 0) {
    *why = std::strerror(errno);
    return false;
  }
  if (!S_ISREG(st.st_mode)) {
    *why = NotRegular(st.st_mode);
    return false;
  }
  if (st.st_size < 0 || static_cast<unsigned long long>(st.st_size) > kMaxInputFileBytes) {
    *why = TooLarge(static_cast<long long>(st.st_size));
    return false;
  }
  try {
    text->clear();
    text->resize(static_cast<std::size_t>(st.st_size) + 1);  // one more: a file that grew
    std::size_t got = 0;
    while (got < text->size()) {
      const ssize_t n = read(f.fd, text->data() + got, text->size() - got);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        *why = std::strerror(errno);
        return false;
      }
      if (n == 0) break;
      got += static_cast<std::size_t>(n);
      if (got > kMaxInputFileBytes) {
        *why = TooLarge(static_cast<long long>(got)) + " (it grew while read)";
        return false;
      }
      if (got == text->size()) text->resize(std::min(2 * text->size(), kMaxInputFileBytes + 1));
    }
    text->resize(got);
  } catch (const std::bad_alloc&) {
    *why = kOutOfMemory;
    return false;
  }
  return true;
}

bool WriteAll(int fd, std::string_view text, std::string* why) {
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
      return false;
    }
    done += static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace snooker::server
