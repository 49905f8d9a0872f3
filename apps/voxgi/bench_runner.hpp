#pragma once
// The GPU side of `voxgi bench`: one device, shader compiler and set of plugins for the whole
// bench; the current scene on the GPU; graphs rendered for a number of frames with their
// per-pass timestamps and read-back outputs.

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "engine/gpu/context.hpp"
#include "engine/gpu/shader_compiler.hpp"
#include "engine/graph/compiler.hpp"
#include "engine/graph/executor.hpp"
#include "engine/graph/graph_desc.hpp"
#include "engine/graph/plugin_loader.hpp"
#include "engine/image/image.hpp"
#include "engine/runtime/frame_driver.hpp"
#include "engine/scene/gpu_scene.hpp"
#include "engine/scene/scene.hpp"

namespace voxgi::cli {

// Graph files and scenes parsed once and shared by every configuration that uses them (CPU
// only: usable before any device is opened, to check a whole bench first).
class BenchCatalog {
 public:
  // Throws GraphError / SceneError naming the file.
  const graph::GraphDesc& graph(const std::filesystem::path& file);
  // Loads `source` (built-in name or glTF path) once; a later different source replaces it,
  // so only one scene is in memory at a time.
  scene::Scene& scene(const std::string& source);
  graph::Registry& registry() { return registry_; }
  // Loads the plugins the graph needs, then compiles it for the scene and viewport, and for the
  // device that renders it (without one, device features read as absent).
  graph::CompiledGraph compile(const graph::GraphDesc& desc, const scene::Scene& scene,
                               uint32_t width, uint32_t height,
                               const std::map<std::string, std::string>& overrides,
                               const gpu::Context* device = nullptr);

 private:
  std::map<std::string, std::unique_ptr<graph::GraphDesc>> graphs_;
  std::string scene_source_;
  std::unique_ptr<scene::Scene> scene_;
  graph::Registry registry_;
  graph::PluginLoader loader_{graph::PluginLoader::default_search_dirs()};
};

struct RenderRun {
  // Executor timings of each measured frame (after the warm-up).
  std::vector<std::vector<graph::Executor::PassTiming>> measured;
  // Every graph output after the last frame, as RGBA32F.
  std::map<std::string, image::ImageRGBA32F> outputs;
};

class BenchRenderer {
 public:
  explicit BenchRenderer(const gpu::ContextOptions& options);
  gpu::Context& context() { return *context_; }

  // Renders warmup + frames frames of one view (camera, lights and geometry change only on the
  // first frame, so progressive graphs accumulate and caches are allowed to skip work). The
  // measured frames also report `measured_changes` (BenchSpec::changes), so that the passes
  // that depend on them run again. `on_frame` (optional) is called after each frame with the
  // number of frames done.
  RenderRun render(const graph::CompiledGraph& compiled, const graph::Registry& registry,
                   const scene::Scene& scene, const scene::Camera& camera, uint32_t warmup,
                   uint32_t frames, const std::function<void(uint32_t)>& on_frame = {},
                   runtime::FrameChanges measured_changes = {false, false, false});

 private:
  scene::GpuScene& gpu_scene(const scene::Scene& scene);

  std::unique_ptr<gpu::Context> context_;
  std::unique_ptr<gpu::ShaderCompiler> shaders_;
  const scene::Scene* uploaded_ = nullptr;
  std::string uploaded_source_;
  std::unique_ptr<scene::GpuScene> gpu_scene_;
};

}  // namespace voxgi::cli
