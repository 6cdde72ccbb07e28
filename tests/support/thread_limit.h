// Running code where the system will start only so many more threads, as in a
// container with a pids limit or a user at their process limit: in a forked child
// that runs as an ordinary user (root is not held to the limit) under RLIMIT_NPROC
// set so that exactly `spare` more threads can start. The planner, the calibration
// fit and the server's workers must then do their work, or fail with a message,
// rather than abort.
#pragma once

#include <grp.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <chrono>
#include <exception>
#include <functional>
#include <string>
#include <thread>
#include <vector>

namespace snooker::test_support {

struct LimitedRun {
  bool limited = false;  // false: the limit could not be set here (the reason in `output`)
  int exit_code = -1;    // the body's return value, 70 if it threw; -1 when the child did not exit
  int signal = 0;        // the signal that ended the child (SIGABRT for std::terminate)
  std::string output;    // what the body wrote
};

namespace detail {

// How many threads can be started side by side under the current limit, up to `most`.
inline int StartableThreads(int most) {
  std::atomic<bool> release{false};
  std::vector<std::thread> held;
  for (int i = 0; i < most; ++i) {
    try {
      held.emplace_back([&release] {
        while (!release.load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      });
    } catch (...) {
      break;
    }
  }
  release = true;
  for (std::thread& t : held) t.join();
  // A joined thread's task is counted until the kernel has released it, just after.
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  return static_cast<int>(held.size());
}

[[noreturn]] inline void Finish(int fd, const std::string& text, int code) {
  for (size_t at = 0; at < text.size();) {
    const ssize_t n = write(fd, text.data() + at, text.size() - at);
    if (n <= 0) break;
    at += static_cast<size_t>(n);
  }
  close(fd);
  _exit(code);  // no atexit handlers, no sanitizer's leak scan in the child
}

constexpr int kNotLimited = 77;
constexpr int kThrew = 70;

}  // namespace detail

/// Runs `body` in a child process in which exactly `spare` more threads can start;
/// `body` writes what the test wants to see into its string and returns the exit code.
inline LimitedRun RunWithSpareThreads(int spare, const std::function<int(std::string*)>& body) {
  LimitedRun run;
  int fds[2];
  if (pipe(fds) != 0) {
    run.output = "pipe failed";
    return run;
  }
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    run.output = "fork failed";
    return run;
  }
  if (pid == 0) {
    close(fds[0]);
    if (geteuid() == 0) {
      const gid_t nobody = 65534;
      if (setgroups(0, nullptr) != 0 || setgid(nobody) != 0 || setuid(nobody) != 0) {
        detail::Finish(fds[1], "could not drop to an ordinary user", detail::kNotLimited);
      }
    }
    // Raise the soft limit (the one enforced; an ordinary user cannot raise the hard
    // one again) from one task until exactly `spare` threads start.
    rlimit r{};
    if (getrlimit(RLIMIT_NPROC, &r) != 0) detail::Finish(fds[1], "getrlimit failed", detail::kNotLimited);
    for (rlim_t limit = 1; limit <= 4096 && limit <= r.rlim_max; ++limit) {
      r.rlim_cur = limit;
      if (setrlimit(RLIMIT_NPROC, &r) != 0) break;
      const int startable = detail::StartableThreads(spare + 1);
      if (startable == spare) {
        // The child must never return into the test framework: an exception ends it too.
        std::string out;
        try {
          const int code = body(&out);
          detail::Finish(fds[1], out, code);
        } catch (const std::exception& e) {
          detail::Finish(fds[1], out + "exception: " + e.what(), detail::kThrew);
        } catch (...) {
          detail::Finish(fds[1], out + "exception", detail::kThrew);
        }
      }
      if (startable > spare) break;
    }
    detail::Finish(fds[1], "RLIMIT_NPROC does not limit this process's threads", detail::kNotLimited);
  }
  close(fds[1]);
  std::array<char, 4096> buf;
  ssize_t n;
  while ((n = read(fds[0], buf.data(), buf.size())) > 0) run.output.append(buf.data(), static_cast<size_t>(n));
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (WIFEXITED(status)) {
    run.exit_code = WEXITSTATUS(status);
    run.limited = run.exit_code != detail::kNotLimited;
  } else if (WIFSIGNALED(status)) {
    run.signal = WTERMSIG(status);
    run.limited = true;
  }
  return run;
}

}  // namespace snooker::test_support
