// libFuzzer target: graph files, parsed (includes resolved next to the shipped graphs) and
// compiled against the real pass types of the plugins for the built-in Cornell box at 64 x 64,
// as `voxgi graph check` does; no GPU. Every input compiles or is refused with a GraphError.

#include <cstdint>
#include <filesystem>
#include <string>

#include "engine/graph/compiler.hpp"
#include "engine/graph/graph_desc.hpp"
#include "engine/graph/plugin_loader.hpp"
#include "engine/scene/builtin_scenes.hpp"
#include "tests/fuzz/libfuzzer/fuzz_target.hpp"

namespace {

struct Setup {
  voxgi::graph::Registry registry;
  voxgi::graph::CompileOptions options;
  std::string file_name =
      (std::filesystem::path(VOXGI_SOURCE_DIR) / "graphs" / "fuzz.json").string();

  Setup() {
    try {
      voxgi::graph::PluginLoader(voxgi::graph::PluginLoader::default_search_dirs())
          .load_all(registry);
    } catch (const std::exception& e) {
      voxgi::fuzz::unexpected(std::string("cannot load the pass plugins: ") + e.what());
    }
    const voxgi::scene::Scene cornell = voxgi::scene::make_builtin_scene("cornell");
    options.viewport_width = 64;
    options.viewport_height = 64;
    options.scene_features = cornell.features().as_map();
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const Setup setup;
  const std::string text = voxgi::fuzz::text_of(data, size);
  voxgi::fuzz::accept_or_refuse([&] {
    const voxgi::graph::GraphDesc desc = voxgi::graph::parse_graph(text, setup.file_name);
    voxgi::graph::compile(desc, setup.registry, setup.options);
  });
  return 0;
}
