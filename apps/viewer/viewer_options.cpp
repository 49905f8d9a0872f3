#include "apps/viewer/viewer_options.hpp"

#include <charconv>

namespace voxgi::viewer {
namespace {

uint32_t parse_size(const std::string& option, const std::string& text) {
  uint32_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value < 1 || value > 8192) {
    throw UsageError(option + " '" + text + "': expected a whole number from 1 to 8192");
  }
  return value;
}

}  // namespace

const char* viewer_usage() {
  return "usage: voxgi-viewer [--scene cornell|PATH.gltf|PATH.glb] [--graph A.json[#VARIANT] "
         "[--graph B.json ...]]\n"
         "                    [--script FILE] [--width W] [--height H] [--set pass.param=value "
         "...]\n"
         "                    [--camera NAME] [--device INDEX|NAME] [--out-dir DIR] "
         "[--validation]\n"
         "keys: 1..9 / Tab switch graph, F1 panel, F2 split A/B, F3 difference, F5 reload,\n"
         "      F12 screenshot, C fly/orbit, WASD QE move, right mouse look, left mouse orbit,\n"
         "      Space play/pause, . step, R reset camera, V next variant of the graph, Esc quit\n";
}

ViewerOptions parse_viewer_options(const std::vector<std::string>& args) {
  ViewerOptions options;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= args.size()) throw UsageError(arg + ": expects a value");
      return args[++i];
    };
    if (arg == "--help" || arg == "-h") {
      options.help = true;
    } else if (arg == "--scene") {
      options.scene = value();
    } else if (arg == "--graph") {
      options.graphs.push_back(value());
    } else if (arg == "--script") {
      options.script = value();
    } else if (arg == "--width") {
      options.width = parse_size(arg, value());
    } else if (arg == "--height") {
      options.height = parse_size(arg, value());
    } else if (arg == "--set") {
      options.sets.push_back(value());
    } else if (arg == "--camera") {
      options.camera = value();
    } else if (arg == "--device") {
      options.device = value();
    } else if (arg == "--out-dir") {
      options.out_dir = value();
    } else if (arg == "--validation") {
      options.validation = true;
    } else {
      throw UsageError("unknown argument '" + arg + "'");
    }
  }
  if (options.graphs.empty()) options.graphs.push_back("graphs/default.json");
  if (options.graphs.size() > 9) {
    throw UsageError("--graph: at most 9 graphs (keys 1..9), got " +
                     std::to_string(options.graphs.size()));
  }
  return options;
}

}  // namespace voxgi::viewer
