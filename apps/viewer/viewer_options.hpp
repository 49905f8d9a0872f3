#pragma once
// The viewer's command line.

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace voxgi::viewer {

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ViewerOptions {
  std::string scene = "cornell";
  std::vector<std::string> graphs;  // empty: graphs/default.json
  std::optional<std::string> script;
  uint32_t width = 640;  // the rendered image; the window adds the panel beside it
  uint32_t height = 480;
  std::vector<std::string> sets;  // KEY=VALUE
  std::string camera;
  std::string device;
  std::string out_dir = "out";  // screenshots taken with the key
  bool validation = false;
  bool help = false;
};

// Throws UsageError naming the bad argument.
ViewerOptions parse_viewer_options(const std::vector<std::string>& args);
const char* viewer_usage();

}  // namespace voxgi::viewer
