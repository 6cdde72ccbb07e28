// Subcommands of the `snooker` command. Each takes the arguments after its name and
// returns the process exit code: 0 success, 1 failure while running, 2 bad usage or
// bad input (the message on `err` names the bad value).
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace snooker::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

int RunCollide(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int RunSimulate(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int RunServe(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int RunLoadTest(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int RunDemo(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int RunPlan(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int RunSelfPlay(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int RunMatch(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int RunModel(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int RunCalibrate(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int RunRecord(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace snooker::cli
