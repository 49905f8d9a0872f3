#pragma once
// Runs a program as a child process and captures what it prints and how it ended. A deadline
// kills it, so a hanging program fails its test instead of stalling the suite.

#include <chrono>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace voxgi::test {

struct ProcessOptions {
  std::filesystem::path working_dir;  // empty: the caller's
  // Overrides of the caller's environment; std::nullopt removes a variable.
  std::map<std::string, std::optional<std::string>> env;
  std::chrono::milliseconds timeout{60000};
};

struct ProcessResult {
  int exit_code = -1;   // -1 when it did not exit normally
  int term_signal = 0;  // the signal that ended it, 0 when it exited
  bool timed_out = false;
  std::string out;
  std::string err;

  bool exited() const { return term_signal == 0 && !timed_out; }
  // Everything needed to understand a failed expectation, for assertion messages.
  std::string describe() const;
};

ProcessResult run_process(const std::filesystem::path& program,
                          const std::vector<std::string>& args, const ProcessOptions& options = {});

}  // namespace voxgi::test
