#pragma once
// Renders a scene through a graph file on the test GPU context, as `voxgi render` does, and
// gives tests the outputs and the camera that produced them.

#include <glm/glm.hpp>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/gpu/shader_compiler.hpp"
#include "engine/graph/compiler.hpp"
#include "engine/graph/executor.hpp"
#include "engine/graph/pass.hpp"
#include "engine/runtime/frame_driver.hpp"
#include "engine/scene/gpu_scene.hpp"
#include "engine/scene/scene.hpp"

namespace voxgi::test {

struct RenderSetup {
  std::string scene = "cornell";              // a built-in name or a glTF path
  std::optional<scene::Scene> scene_data;     // a scene made by the test (wins over `scene`)
  std::string graph = "graphs/default.json";  // relative to the source tree
  uint32_t width = 128;
  uint32_t height = 128;
  std::map<std::string, std::string> overrides;  // --set
  std::string camera;  // a camera of the scene by name; empty: the first one (or a default)
};

struct RenderedImage {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<float> rgba;
  glm::vec4 at(uint32_t x, uint32_t y) const {
    const size_t i = (static_cast<size_t>(y) * width + x) * 4;
    return {rgba[i], rgba[i + 1], rgba[i + 2], rgba[i + 3]};
  }
};

// Adds a failure for every NaN, Inf or negative value of `image`, naming `what`.
void expect_finite_non_negative(const RenderedImage& image, const std::string& what);

class RenderHarness {
 public:
  explicit RenderHarness(const RenderSetup& setup);
  ~RenderHarness();

  // After the first frame, `changes` says what changed (nothing by default).
  void render(int frames = 1, const runtime::FrameChanges& changes = {false, false, false});
  RenderedImage output(const std::string& name);

  scene::Scene& scene() { return scene_; }
  const scene::Camera& camera() const { return camera_; }
  glm::mat4 view_proj() const;
  graph::Executor& executor() { return *executor_; }
  const graph::CompiledGraph& compiled() const { return compiled_; }

 private:
  RenderSetup setup_;
  scene::Scene scene_;
  scene::Camera camera_;
  graph::Registry registry_;
  graph::CompiledGraph compiled_;
  std::unique_ptr<gpu::ShaderCompiler> shaders_;
  std::unique_ptr<scene::GpuScene> gpu_scene_;
  std::unique_ptr<graph::Executor> executor_;
  std::unique_ptr<runtime::FrameDriver> frames_;
};

}  // namespace voxgi::test
