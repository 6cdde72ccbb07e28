# Writes OUTPUT, a C++ source that defines snooker::server::kBuildVersion (VERSION)
# and kBuildCommit: the commit of the checkout at SOURCE_DIR (12 hex digits, with
# "-dirty" when a tracked file differs from it), or "unknown" outside a git checkout
# or without git. Run at every build (server/CMakeLists.txt): cmake -DSOURCE_DIR=...
# -DOUTPUT=... -DVERSION=... -DGIT=... -P build_info.cmake. The file is written only
# when its text changes, so that a build of the same commit compiles nothing again.
cmake_minimum_required(VERSION 3.25)

set(commit unknown)
if(GIT)
  execute_process(COMMAND "${GIT}" -C "${SOURCE_DIR}" rev-parse --short=12 HEAD
                  OUTPUT_VARIABLE head RESULT_VARIABLE head_failed OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(head_failed EQUAL 0 AND head MATCHES "^[0-9a-f]+$")
    set(commit "${head}")
    execute_process(COMMAND "${GIT}" -C "${SOURCE_DIR}" status --porcelain --untracked-files=no
                    OUTPUT_VARIABLE changes RESULT_VARIABLE status_failed ERROR_QUIET)
    if(NOT status_failed EQUAL 0 OR NOT changes STREQUAL "")
      string(APPEND commit "-dirty")
    endif()
  endif()
endif()

set(text "// Generated at build time by server/build_info.cmake (do not edit).
#include \"server/build_info.h\"

namespace snooker::server {

const char* const kBuildVersion = \"${VERSION}\";
const char* const kBuildCommit = \"${commit}\";

}  // namespace snooker::server
")
set(old "")
if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" old)
endif()
if(NOT old STREQUAL text)
  file(WRITE "${OUTPUT}" "${text}")
endif()
