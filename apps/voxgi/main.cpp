// voxgi: the command-line front end. Every error ends in one message and a non-zero exit:
// 2 for a wrong command line, 1 for everything else.

#include <exception>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/voxgi/cli_args.hpp"
#include "apps/voxgi/commands.hpp"
#include "engine/gpu/context.hpp"
#include "engine/runtime/scene_source.hpp"

namespace voxgi::cli {

std::map<std::string, std::string> parse_overrides(const std::vector<std::string>& sets) {
  try {
    return runtime::parse_overrides(sets);
  } catch (const runtime::OverrideError& e) {
    throw UsageError("--set '" + e.setting +
                     "': expected KEY=VALUE, e.g. --set lighting.pcf_radius=2");
  }
}

scene::Camera choose_camera(const scene::Scene& scene, const std::string& name) {
  try {
    return runtime::choose_camera(scene, name);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("--") + e.what());  // "--camera: scene ..."
  }
}

graph::CompileOptions compile_options(const Args& args, const scene::Scene& scene, uint32_t width,
                                      uint32_t height, const gpu::Context* device) {
  graph::CompileOptions options;
  options.viewport_width = width;
  options.viewport_height = height;
  options.scene_features = scene.features().as_map();
  options.overrides = parse_overrides(args.values("set"));
  // --variant NAME is the override "variant" (graph_desc.hpp), so --set variant=NAME works too.
  if (const std::optional<std::string> variant = args.value("variant")) {
    options.overrides[graph::kVariantKey] = *variant;
  }
  options.full_barriers = args.flag("full-barriers");
  options.alias_transients = !args.flag("no-memory-sharing");
  if (device) graph::use_device(options, *device);
  return options;
}

void load_plugins_for(const graph::GraphDesc& desc, graph::Registry& registry) {
  graph::PluginLoader loader(graph::PluginLoader::default_search_dirs());
  loader.load_for_graph(desc, registry);
}

int devices_command(const std::vector<std::string>& args) {
  if (!args.empty()) throw UsageError("voxgi devices: takes no arguments");
  const std::vector<std::string> devices = gpu::Context::list_devices();
  if (devices.empty()) {
    std::cout << "no Vulkan device found: install mesa-vulkan-drivers (lavapipe) or a GPU driver\n";
    return 1;
  }
  for (const std::string& device : devices) std::cout << device << "\n";
  return 0;
}

}  // namespace voxgi::cli

namespace {

constexpr const char* kUsage =
    "usage: voxgi <command> [options]\n"
    "commands:\n"
    "  render          render a scene through a graph to PNG and EXR (voxgi render --help)\n"
    "  graph check     validate a graph file\n"
    "  graph explain   print the compiled schedule, culled passes and resources\n"
    "  passes          list the registered pass types and their parameters\n"
    "  devices         list the Vulkan devices\n"
    "  bench           measure graphs against a reference: results and report (voxgi bench "
    "--help)\n";

}  // namespace

int main(int argc, char** argv) {
  using namespace voxgi::cli;
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    std::cout << kUsage;
    return args.empty() ? 2 : 0;
  }
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  try {
    if (args[0] == "render") return render_command(rest);
    if (args[0] == "graph") return graph_command(rest);
    if (args[0] == "passes") return passes_command(rest);
    if (args[0] == "devices") return devices_command(rest);
    if (args[0] == "bench") return bench_command(rest);
    std::vector<std::string> commands = {"render", "graph", "passes", "devices", "bench"};
    std::string message = "unknown command '" + args[0] + "'";
    if (std::string close = closest_match(args[0], commands); !close.empty()) {
      message += " (did you mean '" + close + "'?)";
    }
    throw UsageError(message);
  } catch (const UsageError& e) {
    std::cerr << "voxgi: error: " << e.what() << "\n" << kUsage;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "voxgi: error: " << e.what() << "\n";
    return 1;
  }
}
