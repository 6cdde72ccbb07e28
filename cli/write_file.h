// Writing an output file named on the command line: every byte reaches the file or
// the command says why. A buffered stream checked before its buffer is flushed says
// nothing of a full disk; this writes through and checks the close as well.
#pragma once

#include <ostream>
#include <string>

namespace snooker::cli {

/// Writes `text` to the file at `path` (created, or truncated) and closes it. On
/// failure says on `err` "<command>: cannot write '<path>': <reason>", the system's
/// reason ("No space left on device", "Permission denied", "Is a directory"), and
/// returns false. `command` is the command's name ("snooker plan").
bool WriteOutputFile(const std::string& path, const std::string& text, const std::string& command,
                     std::ostream& err);

}  // namespace snooker::cli
