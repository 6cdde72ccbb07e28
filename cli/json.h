// Printing API messages as JSON on the command line (Protobuf's JSON form, every
// field printed, lowerCamelCase names: the names tools outside the project read).
#pragma once

#include <google/protobuf/message.h>

#include <ostream>

namespace snooker::cli {

/// Prints `message` as one line of JSON on `out`; on failure says so on `err`,
/// prefixed by `command`, and returns false.
bool PrintJson(const google::protobuf::Message& message, const char* command, std::ostream& out,
               std::ostream& err);

}  // namespace snooker::cli
