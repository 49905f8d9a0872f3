#pragma once
// A small command-line parser: `--name value`, `--name=value`, repeatable options and flags.
// Every mistake is a UsageError that names the command and the option.

#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace voxgi::cli {

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct OptionSpec {
  std::string name;  // without "--"
  bool takes_value = true;
  bool repeatable = false;
  std::string value_name;  // for the help text
  std::string doc;
};

class Args {
 public:
  Args(std::string command, std::vector<OptionSpec> specs);

  // Throws UsageError for unknown options (with a did-you-mean), missing values and repeats.
  void parse(const std::vector<std::string>& argv);

  bool flag(const std::string& name) const { return flags_.count(name) != 0; }
  std::optional<std::string> value(const std::string& name) const;
  std::string value_or(const std::string& name, const std::string& fallback) const;
  std::vector<std::string> values(const std::string& name) const;
  const std::vector<std::string>& positional() const { return positional_; }
  // Integer in [min, max]; throws UsageError naming the option otherwise.
  int integer(const std::string& name, int fallback, int min, int max) const;

  std::string help() const;
  const std::string& command() const { return command_; }

 private:
  const OptionSpec* find(const std::string& name) const;

  std::string command_;
  std::vector<OptionSpec> specs_;
  std::map<std::string, std::vector<std::string>> values_;
  std::set<std::string> flags_;
  std::vector<std::string> positional_;
};

// Edit distance based suggestion among candidates; empty when none is close.
std::string closest_match(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace voxgi::cli
