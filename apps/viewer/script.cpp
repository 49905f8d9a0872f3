#include "apps/viewer/script.hpp"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <sstream>

namespace voxgi::viewer {
namespace {

struct Arity {
  size_t min, max;
  const char* usage;
};

const std::map<std::string, Arity>& commands() {
  static const std::map<std::string, Arity> table = {
      {"frames", {1, 1, "frames N"}},
      {"key", {1, 1, "key NAME"}},
      {"set", {1, 1, "set pass.param=value"}},
      {"graph", {1, 1, "graph N"}},
      {"variant", {1, 1, "variant NAME|none"}},
      {"split", {1, 1, "split on|off"}},
      {"compare", {1, 1, "compare N"}},
      {"wipe", {1, 1, "wipe X (0..1)"}},
      {"diff", {1, 2, "diff on|off [GAIN]"}},
      {"inspect", {1, 3, "inspect RESOURCE|off [LEVEL [SLICE]]"}},
      {"exposure", {1, 1, "exposure EV"}},
      {"camera", {1, 1, "camera NAME|fly|orbit"}},
      {"move", {3, 3, "move RIGHT UP FORWARD (meters)"}},
      {"turn", {2, 2, "turn YAW PITCH (degrees)"}},
      {"light", {3, 5, "light INDEX intensity V | color R G B | position X Y Z | direction X Y Z"}},
      {"play", {0, 0, "play"}},
      {"pause", {0, 0, "pause"}},
      {"step", {0, 1, "step [N]"}},
      {"screenshot", {1, 1, "screenshot PATH"}},
      {"window-shot", {1, 1, "window-shot PATH.png"}},
      {"timings", {1, 1, "timings PATH.json"}},
      {"edit-check", {0, 0, "edit-check"}},
      {"wait-for", {1, 2, "wait-for FILE [SECONDS]"}},
      {"window", {2, 2, "window WIDTH HEIGHT"}},
      {"open", {1, 1, "open graphs|timings|camera|lights|animation|parameters|inspect"}},
      {"quit", {0, 0, "quit"}},
  };
  return table;
}

}  // namespace

std::vector<std::string> script_command_names() {
  std::vector<std::string> names;
  for (const auto& [name, arity] : commands()) names.push_back(name);
  return names;
}

std::vector<ScriptCommand> parse_script(const std::string& text, const std::string& file_name) {
  std::vector<ScriptCommand> result;
  std::istringstream lines(text);
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    ScriptCommand command;
    command.line = number;
    if (!(words >> command.name)) continue;
    for (std::string word; words >> word;) command.args.push_back(word);
    const auto found = commands().find(command.name);
    const std::string where = file_name + ":" + std::to_string(number) + ": ";
    if (found == commands().end()) {
      std::string known;
      for (const std::string& name : script_command_names())
        known += (known.empty() ? "" : ", ") + name;
      throw ScriptError(where + "unknown command '" + command.name + "' (commands: " + known + ")");
    }
    const Arity& arity = found->second;
    if (command.args.size() < arity.min || command.args.size() > arity.max) {
      throw ScriptError(where + "'" + command.name + "' takes " + std::to_string(arity.min) +
                        (arity.max != arity.min ? " to " + std::to_string(arity.max) : "") +
                        " argument(s): " + arity.usage);
    }
    if (command.name == "key" && key_code(command.args[0]) < 0) {
      throw ScriptError(where + "unknown key '" + command.args[0] +
                        "' (A-Z, 0-9, F1-F12, Tab, Space, Escape, Period)");
    }
    if (command.name == "set" && command.args[0].find('=') == std::string::npos) {
      throw ScriptError(where + "'set " + command.args[0] + "': expected pass.param=value");
    }
    result.push_back(std::move(command));
  }
  return result;
}

std::vector<ScriptCommand> load_script(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw ScriptError(file.string() + ": cannot read the script file");
  std::stringstream text;
  text << in.rdbuf();
  return parse_script(text.str(), file.string());
}

int key_code(const std::string& name) {
  std::string upper = name;
  std::transform(upper.begin(), upper.end(), upper.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  if (upper.size() == 1) {
    const char c = upper[0];
    if (c >= 'A' && c <= 'Z') return GLFW_KEY_A + (c - 'A');
    if (c >= '0' && c <= '9') return GLFW_KEY_0 + (c - '0');
    if (c == '.') return GLFW_KEY_PERIOD;
  }
  if (upper.size() >= 2 && upper[0] == 'F') {
    const std::string digits = upper.substr(1);
    if (std::all_of(digits.begin(), digits.end(),
                    [](char c) { return std::isdigit(static_cast<unsigned char>(c)); })) {
      const int n = std::stoi(digits);
      if (n >= 1 && n <= 12) return GLFW_KEY_F1 + (n - 1);
    }
  }
  if (upper == "TAB") return GLFW_KEY_TAB;
  if (upper == "SPACE") return GLFW_KEY_SPACE;
  if (upper == "ESCAPE" || upper == "ESC") return GLFW_KEY_ESCAPE;
  if (upper == "PERIOD") return GLFW_KEY_PERIOD;
  return -1;
}

}  // namespace voxgi::viewer
