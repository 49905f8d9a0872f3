#pragma once
// Scripted viewer sessions (--script FILE): one command per line, run in order between frames,
// so tests and demos can drive the viewer without a person. docs/viewer.md lists the commands.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace voxgi::viewer {

struct ScriptCommand {
  std::string name;               // "frames", "key", "set", ...
  std::vector<std::string> args;  // the words after the name ("set" keeps "k=v" as one word)
  int line = 0;
};

class ScriptError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Parses and checks every line (command names and argument counts). '#' starts a comment.
// Throws ScriptError "FILE:LINE: ..." naming the first bad line.
std::vector<ScriptCommand> parse_script(const std::string& text, const std::string& file_name);
std::vector<ScriptCommand> load_script(const std::filesystem::path& file);

// The command names parse_script() accepts, for messages and docs.
std::vector<std::string> script_command_names();

// GLFW key code for a key name ("W", "3", "F2", "Tab", "Space", "Escape", "Period"); -1 when
// unknown.
int key_code(const std::string& name);

}  // namespace voxgi::viewer
