#include "tests/common/test_graph_gpu.hpp"

#include <filesystem>
#include <vector>

#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {

graph::CompileOptions test_compile_options(const scene::Scene& scene, uint32_t width,
                                           uint32_t height,
                                           std::map<std::string, std::string> overrides) {
  graph::CompileOptions options;
  options.viewport_width = width;
  options.viewport_height = height;
  options.scene_features = scene.features().as_map();
  options.overrides = std::move(overrides);
  return options;
}

TestGraphGpu::TestGraphGpu(const graph::Registry& registry, const graph::CompiledGraph& compiled,
                           const scene::Scene& scene) {
  gpu::Context& context = gpu_context();
  shaders = std::make_unique<gpu::ShaderCompiler>(
      std::vector<std::filesystem::path>{std::filesystem::path(VOXGI_SOURCE_DIR) / "shaders"},
      gpu::ShaderCompiler::default_cache_dir());
  gpu_scene = std::make_unique<scene::GpuScene>(context, scene);
  executor = std::make_unique<graph::Executor>(context, *shaders, registry);
  executor->build(compiled, scene, *gpu_scene);
}

TestGraphGpu::~TestGraphGpu() = default;

}  // namespace voxgi::test
