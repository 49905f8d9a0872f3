#include "render_harness.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "engine/graph/graph_desc.hpp"
#include "engine/graph/plugin_loader.hpp"
#include "engine/scene/builtin_scenes.hpp"
#include "engine/scene/gltf_loader.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {

RenderHarness::RenderHarness(const RenderSetup& setup) : setup_(setup) {
  const std::filesystem::path scene_path(setup.scene);
  const std::string ext = scene_path.extension().string();
  if (setup.scene_data) {
    scene_ = *setup.scene_data;
  } else {
    scene_ = (ext == ".gltf" || ext == ".glb") ? scene::load_gltf(scene_path)
                                               : scene::make_builtin_scene(setup.scene);
  }
  scene_.update_transforms();
  if (!setup.camera.empty()) {
    // By the camera's name or by the name of the node that carries it.
    const scene::Camera* chosen = scene_.find_camera(setup.camera);
    std::string names;
    for (const scene::Camera& c : scene_.cameras) {
      const bool has_node = c.node >= 0 && size_t(c.node) < scene_.nodes.size();
      if (!chosen && has_node && scene_.nodes[size_t(c.node)].name == setup.camera) chosen = &c;
      names += " '" + c.name + "'" +
               (has_node ? " (node '" + scene_.nodes[size_t(c.node)].name + "')" : "");
    }
    if (!chosen) {
      throw std::runtime_error(scene_.source + ": no camera named '" + setup.camera +
                               "'; cameras:" + (names.empty() ? " none" : names));
    }
    camera_ = *chosen;
  } else {
    camera_ = scene_.cameras.empty() ? scene::default_camera(scene_) : scene_.cameras.front();
  }

  const graph::GraphDesc desc =
      graph::load_graph_file(std::filesystem::path(VOXGI_SOURCE_DIR) / setup.graph);
  graph::PluginLoader loader(graph::PluginLoader::default_search_dirs());
  loader.load_for_graph(desc, registry_);
  graph::CompileOptions options;
  options.viewport_width = setup.width;
  options.viewport_height = setup.height;
  options.scene_features = scene_.features().as_map();
  options.overrides = setup.overrides;
  compiled_ = graph::compile(desc, registry_, options);

  gpu::Context& context = gpu_context();
  shaders_ = std::make_unique<gpu::ShaderCompiler>(
      std::vector<std::filesystem::path>{std::filesystem::path(VOXGI_SOURCE_DIR) / "shaders"},
      gpu::ShaderCompiler::default_cache_dir());
  gpu_scene_ = std::make_unique<scene::GpuScene>(context, scene_);
  executor_ = std::make_unique<graph::Executor>(context, *shaders_, registry_);
  executor_->build(compiled_, scene_, *gpu_scene_);
  frames_ = std::make_unique<runtime::FrameDriver>(*executor_);
}

RenderHarness::~RenderHarness() = default;

void expect_finite_non_negative(const RenderedImage& image, const std::string& what) {
  size_t non_finite = 0, negative = 0;
  for (float v : image.rgba) {
    if (!std::isfinite(v)) {
      ++non_finite;
    } else if (v < 0.0f) {
      ++negative;
    }
  }
  EXPECT_EQ(non_finite, 0u) << what << ": NaN or Inf values";
  EXPECT_EQ(negative, 0u) << what << ": negative values";
}

glm::mat4 RenderHarness::view_proj() const {
  const float aspect = static_cast<float>(setup_.width) / static_cast<float>(setup_.height);
  return scene::projection_matrix(camera_, aspect) * scene::view_matrix(camera_);
}

void RenderHarness::render(int frames, const runtime::FrameChanges& changes) {
  const float aspect = static_cast<float>(setup_.width) / static_cast<float>(setup_.height);
  for (int i = 0; i < frames; ++i) {
    frames_->render(runtime::frame_view(camera_, aspect), 0.0, changes);
  }
}

RenderedImage RenderHarness::output(const std::string& name) {
  RenderedImage image;
  image.rgba = executor_->read_output(name, image.width, image.height);
  return image;
}

}  // namespace voxgi::test
