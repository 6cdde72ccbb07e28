// Which build this is: the project's version and the commit it was built from (12
// hex digits, "-dirty" when the checkout had changes; "unknown" when it was not
// built from a git checkout). Read from the checkout at every build
// (server/build_info.cmake). GetModel answers them, `snooker --version` prints them
// and GET /metrics has them as snooker_build_info.
#pragma once

namespace snooker::server {

extern const char* const kBuildVersion;
extern const char* const kBuildCommit;

}  // namespace snooker::server
