// voxgi graph check FILE / voxgi graph explain FILE --scene S

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>

#include "apps/voxgi/cli_args.hpp"
#include "apps/voxgi/commands.hpp"
#include "engine/gpu/context.hpp"
#include "engine/graph/dump.hpp"
#include "engine/graph/memory_budget.hpp"
#include "engine/runtime/scene_source.hpp"

namespace voxgi::cli {
namespace {

Args graph_args(const std::string& verb) {
  return Args(
      "voxgi graph " + verb,
      {{"scene", true, false, "cornell|PATH",
        "scene whose features decide `when` conditions (default cornell)"},
       {"width", true, false, "W", "viewport width for sizes (default 1280)"},
       {"height", true, false, "H", "viewport height for sizes (default 720)"},
       {"set", true, true, "KEY=VALUE", "override a graph or pass parameter"},
       {"variant", true, false, "NAME",
        "compile one of the graph file's named variants (check: default every variant too)"},
       {"dot", true, false, "PATH", "also write the compiled graph as Graphviz DOT"},
       {"dump-dir", true, false, "DIR", "write every compile phase (JSON, DOT) to DIR"},
       {"device", true, false, "INDEX|NAME",
        "query this Vulkan device's features for `when` conditions (default: no device, every "
        "device feature reads as absent) and check the graph's memory against it"},
       {"memory-budget", true, false, "SIZE",
        "check the graph's memory against SIZE (e.g. 8GiB, 512MiB) as if a device had that much"},
       {"full-barriers", false, false, "", "compile with a full barrier between passes"},
       {"no-memory-sharing", false, false, "", "give every transient resource its own memory"},
       {"help", false, false, "", "show this help"}});
}

// "8GiB", "512MiB", "1.5GiB", "4096" (bytes).
uint64_t parse_byte_size(const std::string& option, const std::string& text) {
  static const std::pair<const char*, double> kUnits[] = {
      {"GiB", 1024.0 * 1024 * 1024}, {"MiB", 1024.0 * 1024}, {"KiB", 1024.0}, {"", 1.0}};
  for (const auto& [unit, scale] : kUnits) {
    const size_t n = std::strlen(unit);
    if (text.size() <= n || text.compare(text.size() - n, n, unit) != 0) continue;
    const std::string number = text.substr(0, text.size() - n);
    char* end = nullptr;
    const double value = std::strtod(number.c_str(), &end);
    if (end == number.c_str() + number.size() && value > 0.0 && value * scale < 1e18) {
      return static_cast<uint64_t>(value * scale);
    }
    break;
  }
  throw UsageError(option + ": expected a size such as 8GiB, 512MiB or a byte count, got '" + text +
                   "'");
}

}  // namespace

int graph_command(const std::vector<std::string>& argv) {
  if (argv.empty() || (argv[0] != "check" && argv[0] != "explain")) {
    throw UsageError("voxgi graph: expected 'check FILE' or 'explain FILE [--scene S]'");
  }
  const std::string verb = argv[0];
  Args args = graph_args(verb);
  args.parse({argv.begin() + 1, argv.end()});
  if (args.flag("help")) {
    std::cout << "usage: voxgi graph " << verb << " FILE [options]\n" << args.help();
    return 0;
  }
  if (args.positional().size() != 1) {
    throw UsageError("voxgi graph " + verb + ": expected exactly one graph file");
  }
  const graph::GraphDesc desc =
      graph::load_graph_file(runtime::resolve_graph_path(args.positional()[0]));
  const scene::Scene scene = runtime::load_scene(args.value_or("scene", "cornell"));
  graph::Registry registry;
  load_plugins_for(desc, registry);

  // A graph is checked without a device unless one is named: checking must work on machines
  // without Vulkan, and which device a graph will meet is not known here.
  std::unique_ptr<gpu::Context> device;
  if (const std::optional<std::string> name = args.value("device")) {
    gpu::ContextOptions context_options;
    context_options.device = *name;
    device = std::make_unique<gpu::Context>(context_options);
  }
  const graph::CompileOptions options =
      compile_options(args, scene, static_cast<uint32_t>(args.integer("width", 1280, 1, 16384)),
                      static_cast<uint32_t>(args.integer("height", 720, 1, 16384)), device.get());
  const graph::CompiledGraph compiled = graph::compile(desc, registry, options);
  // The check `voxgi render` makes before allocating anything, made here for a named device
  // or a stated budget.
  if (const std::optional<std::string> budget = args.value("memory-budget")) {
    graph::check_memory_budget(compiled, parse_byte_size("--memory-budget", *budget));
  } else if (device) {
    graph::check_memory_budget(compiled, graph::device_memory_budget(device->physical_device()));
  }

  if (const std::optional<std::string> dump_dir = args.value("dump-dir")) {
    graph::dump_phases(desc, compiled, *dump_dir);
  }
  if (const std::optional<std::string> dot = args.value("dot")) {
    std::ofstream out(*dot);
    if (!out) throw std::runtime_error("--dot: cannot write '" + *dot + "'");
    out << graph::to_dot(compiled);
  }
  if (verb == "check") {
    std::cout << desc.file << ": ok (" << compiled.passes.size() << " passes run, "
              << compiled.culled.size() << " culled for scene '" << scene.source << "'"
              << (compiled.device_conditions.empty() ? ""
                  : device                           ? " and device '" + compiled.device_name + "'"
                           : "; conditions on device features read them as absent, --device D "
                             "queries one")
              << ")\n";
    // Without --variant, every variant the file names must compile too.
    if (!options.overrides.count(graph::kVariantKey)) {
      for (const graph::VariantDesc& variant : desc.variants) {
        graph::CompileOptions with = options;
        with.overrides[graph::kVariantKey] = variant.name;
        try {
          const graph::CompiledGraph v = graph::compile(desc, registry, with);
          std::cout << desc.file << ": variant '" << variant.name << "': ok (" << v.passes.size()
                    << " passes run, " << v.culled.size() << " culled)\n";
        } catch (const graph::GraphError&) {
          std::cerr << "voxgi: " << desc.file << ": variant '" << variant.name << "':\n";
          throw;
        }
      }
    }
  } else {
    std::cout << "scene: " << scene.source << "\n" << graph::explain(compiled);
  }
  return 0;
}

}  // namespace voxgi::cli
