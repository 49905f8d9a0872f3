#pragma once
// What every front end needs once per process: the Vulkan context, the shader compiler, the
// pass registry with its plugins, and the scene on the CPU and the GPU. Graphs run on it
// through GraphInstance (graph_instance.hpp); several may share one Runtime.

#include <memory>
#include <string>
#include <vector>

#include "engine/gpu/context.hpp"
#include "engine/gpu/shader_compiler.hpp"
#include "engine/graph/graph_desc.hpp"
#include "engine/graph/pass.hpp"
#include "engine/graph/plugin_loader.hpp"
#include "engine/scene/gpu_scene.hpp"
#include "engine/scene/scene.hpp"

namespace voxgi::runtime {

bool validation_from_environment();

struct RuntimeOptions {
  std::string device;  // "" automatic, an index or a name substring
  // The Khronos validation layer; on by default when the environment has VOXGI_VALIDATION=1.
  bool validation = validation_from_environment();
  // Extra Vulkan extensions, e.g. for a window surface and a swapchain.
  std::vector<const char*> instance_extensions;
  std::vector<const char*> device_extensions;
};

class Runtime {
 public:
  // Throws gpu::Error when no device fits, scene::SceneError for a scene the GPU copy rejects.
  Runtime(const RuntimeOptions& options, scene::Scene scene);
  ~Runtime();
  Runtime(const Runtime&) = delete;
  Runtime& operator=(const Runtime&) = delete;

  gpu::Context& context() { return *context_; }
  gpu::ShaderCompiler& shaders() { return *shaders_; }
  const graph::Registry& registry() const { return registry_; }
  scene::Scene& scene() { return scene_; }
  scene::GpuScene& gpu_scene() { return *gpu_scene_; }

  // Loads the plugin families a graph names (each once). Throws graph::PluginError.
  void load_plugins_for(const graph::GraphDesc& desc);
  // Every plugin found, e.g. to list all pass types.
  void load_all_plugins();

  // Evaluates the scene's animations at `time_seconds` and uploads what moved. Returns true
  // when anything moved.
  bool animate(double time_seconds);
  // Re-uploads transforms and lights after the caller edited the scene (e.g. moved a light).
  void upload_scene();

 private:
  std::unique_ptr<gpu::Context> context_;
  std::unique_ptr<gpu::ShaderCompiler> shaders_;
  graph::Registry registry_;
  graph::PluginLoader plugins_;
  scene::Scene scene_;
  std::unique_ptr<scene::GpuScene> gpu_scene_;
};

}  // namespace voxgi::runtime
