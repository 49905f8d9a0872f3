#pragma once
// The subcommands of `voxgi`. Each returns the process exit code; errors are thrown and
// reported by main().

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "engine/graph/compiler.hpp"
#include "engine/graph/pass.hpp"
#include "engine/graph/plugin_loader.hpp"
#include "engine/scene/scene.hpp"

namespace voxgi::cli {

int render_command(const std::vector<std::string>& args);
int graph_command(const std::vector<std::string>& args);
int passes_command(const std::vector<std::string>& args);
int devices_command(const std::vector<std::string>& args);
int bench_command(const std::vector<std::string>& args);

// "--set key=value" arguments → overrides (runtime::parse_overrides); throws UsageError naming
// the bad argument.
std::map<std::string, std::string> parse_overrides(const std::vector<std::string>& sets);

// runtime::choose_camera, its error naming the --camera option.
scene::Camera choose_camera(const scene::Scene& scene, const std::string& name);

class Args;

// The compile options `render` and `graph` both take from their command line (--set,
// --full-barriers, --no-memory-sharing) for a scene and viewport, and for the device that will
// run the graph (null: none, so device features read as absent).
graph::CompileOptions compile_options(const Args& args, const scene::Scene& scene, uint32_t width,
                                      uint32_t height, const gpu::Context* device);

// Loads the plugins a graph needs into `registry`.
void load_plugins_for(const graph::GraphDesc& desc, graph::Registry& registry);

}  // namespace voxgi::cli
