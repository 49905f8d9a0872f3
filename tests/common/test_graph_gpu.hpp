#pragma once
// What a test needs on the GPU to run a compiled graph on a scene: a shader compiler over the
// source tree's shaders/, the scene's GPU copy, and an executor built for the graph. Members
// are destroyed executor first.

#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include "engine/gpu/shader_compiler.hpp"
#include "engine/graph/compiler.hpp"
#include "engine/graph/executor.hpp"
#include "engine/scene/gpu_scene.hpp"
#include "engine/scene/scene.hpp"

namespace voxgi::test {

// Compile options for a width x height viewport with the scene's features and `overrides`.
graph::CompileOptions test_compile_options(const scene::Scene& scene, uint32_t width,
                                           uint32_t height,
                                           std::map<std::string, std::string> overrides);

struct TestGraphGpu {
  // Builds on the test GPU context (gpu_context()); `registry` and `scene` must outlive this.
  TestGraphGpu(const graph::Registry& registry, const graph::CompiledGraph& compiled,
               const scene::Scene& scene);
  ~TestGraphGpu();

  std::unique_ptr<gpu::ShaderCompiler> shaders;
  std::unique_ptr<scene::GpuScene> gpu_scene;
  std::unique_ptr<graph::Executor> executor;
};

}  // namespace voxgi::test
