#include "tests/fuzz/fuzz_inputs.hpp"

#include <cmath>
#include <fstream>
#include <stdexcept>

#include "apps/voxgi/bench_spec.hpp"
#include "engine/graph/expression.hpp"
#include "engine/graph/graph_desc.hpp"
#include "engine/graph/json.hpp"
#include "engine/graph/plugin_loader.hpp"
#include "engine/scene/builtin_scenes.hpp"
#include "engine/scene/gltf_loader.hpp"

namespace voxgi::fuzz {
namespace {

const std::filesystem::path kRepo = VOXGI_SOURCE_DIR;

void check_numbers(const graph::json::Value& value) {
  if (value.is_number() && std::isfinite(value.as_number())) {
    const std::string text = graph::json::number_text(value.as_number());
    if (graph::json::parse(text, "number_text").as_number() != value.as_number()) {
      throw std::logic_error("number_text(" + text + ") does not read back as the same number");
    }
  } else if (value.is_array()) {
    for (const graph::json::Value& item : value.items()) check_numbers(item);
  } else if (value.is_object()) {
    for (const auto& member : value.members()) check_numbers(member.value);
  }
}

graph::ExpressionEnv expression_environment() {
  graph::ExpressionEnv env;
  env.params = {{"voxel.resolution", 64}, {"shadow.max_lights", 4}};
  env.identifiers = {{"viewport", 800},        {"viewport.width", 800},
                     {"viewport.height", 600}, {"scene.light_count", 2},
                     {"scene.has_glossy", 0},  {"device.geometry_shader", 1}};
  env.identifier_kind = "scene feature";
  env.identifier_help = "scene.light_count, scene.has_glossy";
  env.identifier_families = {{"device.", "device feature"}};
  return env;
}

}  // namespace

void run_json(const std::string& text) {
  check_numbers(graph::json::parse(text, "fuzz.json"));
}

GraphInput::GraphInput() {
  graph::PluginLoader(graph::PluginLoader::default_search_dirs()).load_all(registry_);
  options_.viewport_width = 64;
  options_.viewport_height = 64;
  options_.scene_features = scene::make_builtin_scene("cornell").features().as_map();
}

void GraphInput::run(const std::string& text) const {
  const graph::GraphDesc desc = graph::parse_graph(text, (kRepo / "graphs" / "fuzz.json").string());
  graph::compile(desc, registry_, options_);
}

void run_expression(const std::string& text) {
  static const graph::ExpressionEnv env = expression_environment();
  const graph::Expression expression = graph::Expression::parse(text);
  expression.identifiers();
  expression.evaluate(env);
}

void run_bench(const std::string& text) {
  cli::expand_configurations(cli::parse_bench(text, kRepo / "graphs" / "fuzz-bench.json", kRepo));
}

void run_gltf(const std::string& bytes, const std::filesystem::path& scratch) {
  const std::filesystem::path path =
      scratch / (bytes.rfind("glTF", 0) == 0 ? "input.glb" : "input.gltf");
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw std::runtime_error("cannot write " + path.string());
  }
  scene::Scene scene = scene::load_gltf(path);
  scene.instances();
  glm::vec3 lo, hi;
  scene.bounds(lo, hi);
  scene.features();
  if (!scene.animations.empty()) scene.animate(0.5);
}

}  // namespace voxgi::fuzz
