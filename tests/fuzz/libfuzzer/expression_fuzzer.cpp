// libFuzzer target: the expression language of sizes and `when` conditions
// (engine/graph/expression). Every input parses and evaluates or is refused with an
// ExpressionError; the names it may read are those of a graph with two parameters.

#include <cstdint>
#include <string>

#include "engine/graph/expression.hpp"
#include "tests/fuzz/libfuzzer/fuzz_target.hpp"

namespace {

const voxgi::graph::ExpressionEnv& environment() {
  static const voxgi::graph::ExpressionEnv env = [] {
    voxgi::graph::ExpressionEnv e;
    e.params = {{"voxel.resolution", 64}, {"shadow.max_lights", 4}};
    e.identifiers = {{"viewport", 800},        {"viewport.width", 800},
                     {"viewport.height", 600}, {"scene.light_count", 2},
                     {"scene.has_glossy", 0},  {"device.geometry_shader", 1}};
    e.identifier_kind = "scene feature";
    e.identifier_help = "scene.light_count, scene.has_glossy";
    e.identifier_families = {{"device.", "device feature"}};
    return e;
  }();
  return env;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = voxgi::fuzz::text_of(data, size);
  voxgi::fuzz::accept_or_refuse([&] {
    const voxgi::graph::Expression expression = voxgi::graph::Expression::parse(text);
    expression.identifiers();
    expression.evaluate(environment());
  });
  return 0;
}
