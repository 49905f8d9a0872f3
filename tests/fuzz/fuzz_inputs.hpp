#pragma once
// What one fuzz input goes through, per parser: the libFuzzer targets (tests/fuzz/libfuzzer)
// and the replay of their failed inputs (fuzz_regressions_test.cpp) both call these, so an
// input kept under tests/fuzz/regressions/<target>/ runs exactly as the target ran it. Each
// returns normally or throws: a located error (GraphError, ExpressionError, SceneError) is a
// refusal, any other exception a defect.

#include <filesystem>
#include <string>

#include "engine/graph/compiler.hpp"
#include "engine/graph/pass.hpp"

namespace voxgi::fuzz {

// The JSON reader; a number it read, written back with number_text, must read back the same
// (std::logic_error otherwise).
void run_json(const std::string& text);

// Graph files, parsed as if in graphs/ and compiled against the real pass types for the
// built-in Cornell box at 64 × 64, as `voxgi graph check` does; no GPU.
class GraphInput {
 public:
  GraphInput();  // loads the pass plugins
  void run(const std::string& text) const;

 private:
  graph::Registry registry_;
  graph::CompileOptions options_;
};

// The expression language of sizes and `when` conditions, with two parameters and a few scene
// and device names.
void run_expression(const std::string& text);

// Bench files, parsed as if in graphs/ and expanded into their configurations.
void run_bench(const std::string& text);

// glTF up to the CPU scene: the input is written into `scratch` (.glb when it starts with the
// "glTF" magic, .gltf otherwise) and loaded; then its instances, bounds, features and one
// animation step.
void run_gltf(const std::string& bytes, const std::filesystem::path& scratch);

}  // namespace voxgi::fuzz
