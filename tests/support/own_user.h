// A user id no other process on the machine has, for a test that holds a command to a
// per-user limit (RLIMIT_NPROC counts every process of the user): root is exempt from
// such limits, and another user's processes, another test's copy run beside it among
// them, would count against it. The id is numbered from the test's process id, far
// above the ids Debian hands out, so that two tests run side by side differ.
#pragma once

#include <sys/types.h>
#include <unistd.h>

namespace snooker::test_support {

inline uid_t OwnUserId() { return 200000 + static_cast<uid_t>(getpid()); }

}  // namespace snooker::test_support
