// Inputs the libFuzzer targets (tests/fuzz/libfuzzer) failed on, kept under
// tests/fuzz/regressions/<target>/ once fixed: each must now load or be refused with the
// project's located error, exactly as the target that found it runs it.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <typeinfo>

#include "apps/voxgi/bench_spec.hpp"
#include "engine/graph/compiler.hpp"
#include "engine/graph/diagnostics.hpp"
#include "engine/graph/expression.hpp"
#include "engine/graph/graph_desc.hpp"
#include "engine/graph/json.hpp"
#include "engine/graph/plugin_loader.hpp"
#include "engine/scene/builtin_scenes.hpp"
#include "engine/scene/gltf_loader.hpp"
#include "tests/scene/gltf_writer.hpp"

namespace voxgi::test {
namespace {

namespace fs = std::filesystem;
const fs::path kRepo = VOXGI_SOURCE_DIR;

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Runs `parse` on every file of tests/fuzz/regressions/<target>; returns how many there were.
int replay(const std::string& target, const std::function<void(const std::string&)>& parse) {
  const fs::path dir = kRepo / "tests" / "fuzz" / "regressions" / target;
  if (!fs::is_directory(dir)) return 0;
  int count = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    ++count;
    try {
      parse(read(entry.path()));
    } catch (const graph::GraphError&) {
    } catch (const graph::ExpressionError&) {
    } catch (const scene::SceneError&) {
    } catch (const std::exception& e) {
      ADD_FAILURE() << entry.path() << " threw " << typeid(e).name() << ": " << e.what();
    }
  }
  return count;
}

TEST(FuzzRegressions, JsonAndGraphFiles) {
  int count =
      replay("json", [](const std::string& text) { graph::json::parse(text, "fuzz.json"); });
  graph::Registry registry;
  graph::PluginLoader(graph::PluginLoader::default_search_dirs()).load_all(registry);
  graph::CompileOptions options;
  options.viewport_width = 64;
  options.viewport_height = 64;
  options.scene_features = scene::make_builtin_scene("cornell").features().as_map();
  count += replay("graph", [&](const std::string& text) {
    graph::compile(graph::parse_graph(text, (kRepo / "graphs" / "fuzz.json").string()), registry,
                   options);
  });
  if (count == 0) GTEST_SKIP() << "no inputs under tests/fuzz/regressions/{json,graph}";
}

TEST(FuzzRegressions, ExpressionsAndBenchFiles) {
  int count = 0;
  graph::ExpressionEnv env;
  env.params = {{"voxel.resolution", 64}, {"shadow.max_lights", 4}};
  env.identifiers = {{"viewport", 800},        {"viewport.width", 800},
                     {"viewport.height", 600}, {"scene.light_count", 2},
                     {"scene.has_glossy", 0},  {"device.geometry_shader", 1}};
  env.identifier_kind = "scene feature";
  env.identifier_help = "scene.light_count, scene.has_glossy";
  env.identifier_families = {{"device.", "device feature"}};
  count += replay("expression", [&](const std::string& text) {
    const graph::Expression expression = graph::Expression::parse(text);
    expression.identifiers();
    expression.evaluate(env);
  });
  count += replay("bench", [](const std::string& text) {
    cli::expand_configurations(cli::parse_bench(text, kRepo / "graphs" / "fuzz-bench.json", kRepo));
  });
  if (count == 0) GTEST_SKIP() << "no inputs under tests/fuzz/regressions/{expression,bench}";
}

TEST(FuzzRegressions, GltfFiles) {
  const fs::path dir = fresh_dir("fuzz_regressions");
  const int count = replay("gltf", [&](const std::string& bytes) {
    const fs::path path = dir / (bytes.rfind("glTF", 0) == 0 ? "input.glb" : "input.gltf");
    std::ofstream(path, std::ios::binary) << bytes;
    scene::Scene scene = scene::load_gltf(path);
    scene.instances();
    glm::vec3 lo, hi;
    scene.bounds(lo, hi);
    scene.features();
    if (!scene.animations.empty()) scene.animate(0.5);
  });
  fs::remove_all(dir);
  if (count == 0) GTEST_SKIP() << "no inputs under tests/fuzz/regressions/gltf";
}

}  // namespace
}  // namespace voxgi::test
