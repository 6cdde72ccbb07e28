// Writing an output file named on the command line: every byte reaches the file or
// the command says why. A buffered stream checked before its buffer is flushed says
// nothing of a full disk; this writes through and checks the close as well.
#pragma once

#include <ostream>
#include <string>

namespace snooker::cli {

/// Writes `text` to the file at `path` (created, or truncated) and closes it. On
/// failure returns false and sets `why` to the system's reason ("No space left on
/// device", "Permission denied", "Is a directory").
bool WriteOutputFile(const std::string& path, const std::string& text, std::string* why);

/// The same for `command` ("snooker plan"): on failure says on `err`
/// "<command>: cannot write '<path>': <reason>" and returns false.
bool WriteOutputFile(const std::string& path, const std::string& text, const std::string& command,
                     std::ostream& err);

}  // namespace snooker::cli
