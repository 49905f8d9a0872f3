#include "engine/runtime/runtime.hpp"

#include <cstdlib>

namespace voxgi::runtime {

bool validation_from_environment() {
  const char* value = std::getenv("VOXGI_VALIDATION");
  return value && std::string(value) == "1";
}

Runtime::Runtime(const RuntimeOptions& options, scene::Scene scene)
    : plugins_(graph::PluginLoader::default_search_dirs()), scene_(std::move(scene)) {
  gpu::ContextOptions context_options;
  context_options.device = options.device;
  context_options.validation = options.validation;
  context_options.instance_extensions = options.instance_extensions;
  context_options.device_extensions = options.device_extensions;
  context_ = std::make_unique<gpu::Context>(context_options);
  shaders_ = std::make_unique<gpu::ShaderCompiler>(
      std::vector<std::filesystem::path>{gpu::ShaderCompiler::default_shader_root()},
      gpu::ShaderCompiler::default_cache_dir());
  scene_.update_transforms();
  gpu_scene_ = std::make_unique<scene::GpuScene>(*context_, scene_);
}

Runtime::~Runtime() {
  if (context_) context_->wait_idle();
}

void Runtime::load_plugins_for(const graph::GraphDesc& desc) {
  plugins_.load_for_graph(desc, registry_);
}

void Runtime::load_all_plugins() {
  plugins_.load_all(registry_);
}

bool Runtime::animate(double time_seconds) {
  if (scene_.animations.empty()) return false;
  const bool moved = scene_.animate(time_seconds);
  if (moved) gpu_scene_->update(scene_);
  return moved;
}

void Runtime::upload_scene() {
  gpu_scene_->update(scene_);
}

}  // namespace voxgi::runtime
