// Running code where the system will start only so many more threads, as in a
// container with a pids limit or a user at their process limit. The planner, the
// calibration fit and the server's workers must then do their work, or fail with a
// message, rather than abort.
//
// The code runs in a fresh copy of the test binary, started for the current test
// alone (fork and exec, so that no lock another thread of this process held at the
// fork can stall it), which runs as a user of its own (root is not held to the
// limit, and no other process may count against it) under an RLIMIT_NPROC set so
// that exactly `spare` more threads can start. Without root the tests skip. A test
// calls RunWithSpareThreads once: the copy runs the test from its start and, at that
// call, runs `body` and reports through a pipe instead of returning.
#pragma once

#include <fcntl.h>
#include <grp.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/own_user.h"

extern char** environ;

namespace snooker::test_support {

struct LimitedRun {
  bool limited = false;  // false: the limit could not be set here (the reason in `output`)
  int exit_code = -1;    // the body's return value, 70 if it threw; -1 when the copy did not exit
  int signal = 0;        // the signal that ended the copy (SIGABRT for std::terminate)
  std::string output;    // what the body wrote
};

namespace detail {

constexpr int kThrew = 70;
constexpr int kNotLimited = 77;
constexpr const char* kFdVariable = "SNOOKER_TEST_SPARE_THREADS_FD";

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
  _exit(code);  // no atexit handlers, no sanitizer's leak scan, no return to the test
}

// In the copy: become a user of its own, find the soft limit under which exactly
// `spare` threads start, run `body` and end the process. The user is OwnUserId(),
// numbered from the copy's process id (own_user.h); only root can take such a user.
[[noreturn]] inline void RunLimited(int spare, int fd, const std::function<int(std::string*)>& body) {
  if (geteuid() != 0) Finish(fd, "needs root, to run the copy as a user of its own", kNotLimited);
  const uid_t own = OwnUserId();
  if (setgroups(0, nullptr) != 0 || setgid(own) != 0 || setuid(own) != 0) {
    Finish(fd, "could not become a user of its own", kNotLimited);
  }
  // The soft limit is the one enforced; an ordinary user cannot raise the hard one.
  rlimit r{};
  if (getrlimit(RLIMIT_NPROC, &r) != 0) Finish(fd, "getrlimit failed", kNotLimited);
  for (rlim_t limit = 1; limit <= 4096 && limit <= r.rlim_max; ++limit) {
    r.rlim_cur = limit;
    if (setrlimit(RLIMIT_NPROC, &r) != 0) break;
    const int startable = StartableThreads(spare + 1);
    if (startable > spare) break;
    if (startable < spare) continue;
    std::string out;
    try {
      const int code = body(&out);
      Finish(fd, out, code);
    } catch (const std::exception& e) {
      Finish(fd, out + "exception: " + e.what(), kThrew);
    } catch (...) {
      Finish(fd, out + "exception", kThrew);
    }
  }
  Finish(fd, "RLIMIT_NPROC does not limit this process's threads", kNotLimited);
}

}  // namespace detail

/// Runs `body` in a copy of this test binary in which exactly `spare` more threads
/// can start (see above; once per test); `body` writes what the test wants to see
/// into its string and returns the exit code. The copy is killed after two minutes.
inline LimitedRun RunWithSpareThreads(int spare, const std::function<int(std::string*)>& body) {
  if (const char* fd = std::getenv(detail::kFdVariable)) {
    detail::RunLimited(spare, std::atoi(fd), body);  // in the copy: never returns
  }
  LimitedRun run;
  const testing::TestInfo* test = testing::UnitTest::GetInstance()->current_test_info();
  int fds[2];
  if (test == nullptr || pipe(fds) != 0) {
    run.output = "no test or no pipe";
    return run;
  }
  // Everything the copy needs is made before the fork: after it, only exec.
  const std::string filter = std::string("--gtest_filter=") + test->test_suite_name() + "." + test->name();
  std::vector<std::string> env_text;
  for (char** e = environ; *e != nullptr; ++e) env_text.emplace_back(*e);
  env_text.push_back(std::string(detail::kFdVariable) + "=" + std::to_string(fds[1]));
  std::vector<char*> envp;
  for (std::string& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);
  std::string exe = "/proc/self/exe", flt = filter;
  char* argv[] = {exe.data(), flt.data(), nullptr};
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    run.output = "fork failed";
    return run;
  }
  if (pid == 0) {
    close(fds[0]);
    const int null = open("/dev/null", O_WRONLY);
    if (null >= 0) dup2(null, STDOUT_FILENO);  // the copy's own test report
    execve(argv[0], argv, envp.data());
    _exit(127);
  }
  close(fds[1]);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(2);
  std::array<char, 4096> buf;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    pollfd p{fds[0], POLLIN, 0};
    if (left.count() <= 0 || poll(&p, 1, static_cast<int>(left.count())) <= 0) {
      kill(pid, SIGKILL);
      run.output += " [killed after two minutes]";
      break;
    }
    const ssize_t n = read(fds[0], buf.data(), buf.size());
    if (n <= 0) break;
    run.output.append(buf.data(), static_cast<size_t>(n));
  }
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (WIFEXITED(status)) {
    run.exit_code = WEXITSTATUS(status);
    run.limited = run.exit_code != detail::kNotLimited && run.exit_code != 127;
  } else if (WIFSIGNALED(status)) {
    run.signal = WTERMSIG(status);
    run.limited = true;
  }
  return run;
}

}  // namespace snooker::test_support
