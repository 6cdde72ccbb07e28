// Reading an input file named by a user (the command line's files, the TLS files the
// server reads again as they rotate): only a regular file, only up to a size limit,
// and a reason otherwise. A path may name anything: a directory, a FIFO that nobody
// writes (reading it would hang), /dev/zero (endless), a file of gigabytes. And the
// other way: the whole of a text written to an open descriptor (the command line's
// output files, the server's in-memory certificate files).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace snooker::server {

/// Largest input file read, bytes (16 MiB: a full table is under 2 KB).
inline constexpr std::size_t kMaxInputFileBytes = 16u << 20;

/// The `why` of ReadInputFile when memory ran out.
inline constexpr const char* kOutOfMemory = "out of memory";

/// Reads the regular file at `path` (at most kMaxInputFileBytes) into `text`. On
/// failure returns false and sets `why` ("is a directory", "is a FIFO (named pipe),
/// not a regular file", "is 17825792 bytes; at most 16777216 are read", "No such file
/// or directory", "out of memory"); never blocks on a FIFO or a device.
bool ReadInputFile(const std::string& path, std::string* text, std::string* why);

/// Writes all of `text` to the open descriptor `fd`. On failure returns false and sets
/// `why` to the system's reason, or "the device took no more bytes". An interrupted
/// write is tried again, at most 100 times in a row.
bool WriteAll(int fd, std::string_view text, std::string* why);

}  // namespace snooker::server
