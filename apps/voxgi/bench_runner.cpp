#include "apps/voxgi/bench_runner.hpp"

#include "engine/runtime/frame_driver.hpp"
#include "engine/runtime/scene_source.hpp"

namespace voxgi::cli {

const graph::GraphDesc& BenchCatalog::graph(const std::filesystem::path& file) {
  const std::string key = file.lexically_normal().string();
  auto it = graphs_.find(key);
  if (it == graphs_.end()) {
    it = graphs_.emplace(key, std::make_unique<graph::GraphDesc>(graph::load_graph_file(file)))
             .first;
  }
  return *it->second;
}

scene::Scene& BenchCatalog::scene(const std::string& source) {
  if (!scene_ || scene_source_ != source) {
    scene_.reset();
    scene_ = std::make_unique<scene::Scene>(runtime::load_scene(source));
    scene_source_ = source;
  }
  return *scene_;
}

graph::CompiledGraph BenchCatalog::compile(const graph::GraphDesc& desc, const scene::Scene& scene,
                                           uint32_t width, uint32_t height,
                                           const std::map<std::string, std::string>& overrides,
                                           const gpu::Context* device) {
  loader_.load_for_graph(desc, registry_);
  graph::CompileOptions options;
  options.viewport_width = width;
  options.viewport_height = height;
  options.scene_features = scene.features().as_map();
  options.overrides = overrides;
  if (device) graph::use_device(options, *device);
  return graph::compile(desc, registry_, options);
}

BenchRenderer::BenchRenderer(const gpu::ContextOptions& options)
    : context_(std::make_unique<gpu::Context>(options)),
      shaders_(std::make_unique<gpu::ShaderCompiler>(
          std::vector<std::filesystem::path>{gpu::ShaderCompiler::default_shader_root()},
          gpu::ShaderCompiler::default_cache_dir())) {}

scene::GpuScene& BenchRenderer::gpu_scene(const scene::Scene& scene) {
  // The catalog keeps one scene at a time, so the address and source identify it.
  if (!gpu_scene_ || uploaded_ != &scene || uploaded_source_ != scene.source) {
    gpu_scene_.reset();
    gpu_scene_ = std::make_unique<scene::GpuScene>(*context_, scene);
    uploaded_ = &scene;
    uploaded_source_ = scene.source;
  }
  return *gpu_scene_;
}

RenderRun BenchRenderer::render(const graph::CompiledGraph& compiled,
                                const graph::Registry& registry, const scene::Scene& scene,
                                const scene::Camera& camera, uint32_t warmup, uint32_t frames,
                                const std::function<void(uint32_t)>& on_frame,
                                runtime::FrameChanges measured_changes) {
  scene::GpuScene& uploaded = gpu_scene(scene);
  graph::Executor executor(*context_, *shaders_, registry);
  executor.build(compiled, scene, uploaded);
  RenderRun run;
  const float aspect =
      static_cast<float>(compiled.viewport_width) / static_cast<float>(compiled.viewport_height);
  runtime::FrameDriver driver(executor);
  const runtime::FrameView view = runtime::frame_view(camera, aspect);
  for (uint32_t frame = 0; frame < warmup + frames; ++frame) {
    driver.render(view, 0.0,
                  frame >= warmup ? measured_changes : runtime::FrameChanges{false, false, false});
    if (frame >= warmup) run.measured.push_back(executor.timings());
    if (on_frame) on_frame(frame + 1);
  }
  for (const auto& [name, resource] : compiled.outputs) {
    (void)resource;
    image::ImageRGBA32F picture;
    picture.pixels = executor.read_output(name, picture.width, picture.height);
    run.outputs.emplace(name, std::move(picture));
  }
  return run;
}

}  // namespace voxgi::cli
