// Running the built `snooker` command from the tests (service and planner suites;
// the test target defines SNOOKER_CLI_PATH).
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

namespace snooker::cli_support {

struct RunResult {
  int exit_code = -1;  // -1: killed by a signal (an abort is not an exit)
  std::string out, err;
};

/// This process's own folder in the test temp folder (ctest runs test cases in parallel
/// processes), made on first use and removed with everything in it when the process
/// exits normally, so that passing runs leave nothing behind.
inline const std::string& TestFolder() {
  struct Folder {
    std::string path = testing::TempDir() + "snooker_tests_" + std::to_string(getpid()) + "/";
    Folder() { std::filesystem::create_directories(path); }
    ~Folder() {
      std::error_code ignored;  // a file still open elsewhere must not abort the exit
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Folder folder;
  return folder.path;
}

/// A path named `name` in this process's test folder.
inline std::string TempPath(const std::string& name) { return TestFolder() + name; }

/// Runs `command` with /bin/sh; stdout and stderr captured apart.
inline RunResult RunShell(const std::string& command) {
  // Unique per process and call.
  static int calls = 0;
  const std::string err_file = TempPath("snooker_cli_stderr_" + std::to_string(++calls) + ".txt");
  const std::string cmd = command + " 2>" + err_file;
  RunResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (p == nullptr) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream f(err_file);
  std::stringstream ss;
  ss << f.rdbuf();
  r.err = ss.str();
  std::remove(err_file.c_str());
  return r;
}

/// Runs the built `snooker` binary with `args` (already shell-quoted where needed).
inline RunResult RunCli(const std::string& args) {
  // Appended in place: GCC 12 warns a false -Wstringop-overflow on the chain of `+`.
  std::string command = SNOOKER_CLI_PATH;
  command += ' ';
  command += args;
  return RunShell(command);
}

/// Shell text that waits (at most 20 s) until `serve_out`, the standard output of a
/// `snooker serve` started in the background, names its port, and sets $port.
inline std::string kWaitForPort(const std::string& serve_out) {
  return "for i in $(seq 200); do grep -q 'on port' " + serve_out + " 2>/dev/null && break; "
         "sleep 0.1; done; port=$(grep -o 'port [0-9]*' " + serve_out + " | cut -d' ' -f2); ";
}

/// Writes `text` to a fresh file in the test temp folder and returns its path.
inline std::string TempFile(const std::string& name, const std::string& text) {
  const std::string path = TempPath(name);
  std::ofstream(path) << text;
  return path;
}

/// The whole text of the file at `path` ("" when it cannot be read).
inline std::string ReadText(const std::string& path) {
  std::ifstream f(path);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

}  // namespace snooker::cli_support
