#pragma once
// One graph running on a Runtime: its description, the compiled graph for a viewport and a
// set of overrides, and the executor that renders it. Switching graphs or reloading one means
// making a new GraphInstance; the old one keeps working until the new one is built, so a
// failed reload never leaves the caller without a running graph.

#include <glm/glm.hpp>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "engine/graph/compiler.hpp"
#include "engine/graph/executor.hpp"
#include "engine/graph/graph_desc.hpp"
#include "engine/image/image.hpp"
#include "engine/runtime/frame_driver.hpp"
#include "engine/scene/scene.hpp"

namespace voxgi::runtime {

class Runtime;

struct GraphSettings {
  uint32_t width = 1280;
  uint32_t height = 720;
  std::map<std::string, std::string> overrides;  // "pass.param" or graph parameter → value
  // Extra outputs (name → resource), e.g. an intermediate image to inspect. Outputs keep
  // their resource alive to the end of the frame and readable.
  std::map<std::string, std::string> extra_outputs;
  bool full_barriers = false;
  bool alias_transients = true;
};

class GraphInstance {
 public:
  // Loads the plugins the graph names, compiles it for the runtime's scene and builds an
  // executor. Throws graph::GraphError / graph::PluginError / gpu::ShaderError with the file,
  // pass and field named.
  GraphInstance(Runtime& runtime, graph::GraphDesc desc, GraphSettings settings);
  // The same from a graph file.
  GraphInstance(Runtime& runtime, const std::filesystem::path& graph_file, GraphSettings settings);
  ~GraphInstance();
  GraphInstance(const GraphInstance&) = delete;
  GraphInstance& operator=(const GraphInstance&) = delete;

  void render(const FrameView& view, double time, const FrameChanges& changes);

  // An output after render(), as RGBA floats (display outputs are display-referred).
  image::ImageRGBA32F read(const std::string& output);
  bool has_output(const std::string& output) const;

  // Per-pass GPU and CPU times of the last frame.
  const std::vector<graph::Executor::PassTiming>& timings() const;

  // A pass parameter changed live ("pass.param"); remembered so that a rebuild keeps it.
  // Returns true when applied without re-running the pass's setup. A parameter that sizes
  // resources compiles the graph again. Throws graph::GraphError.
  bool set_param(const std::string& key, const std::string& value);
  // The current value of a pass parameter as compiled and since edited.
  const graph::ParamValue* param(const std::string& pass, const std::string& name) const;

  const graph::GraphDesc& desc() const { return desc_; }
  const GraphSettings& settings() const { return settings_; }
  const graph::CompiledGraph& compiled() const;
  graph::Executor& executor() { return *executor_; }
  uint64_t frames_rendered() const { return frames_->frames(); }

 private:
  graph::CompiledGraph compile(const GraphSettings& settings) const;

  Runtime& runtime_;
  graph::GraphDesc desc_;
  GraphSettings settings_;
  std::unique_ptr<graph::Executor> executor_;
  std::unique_ptr<FrameDriver> frames_;
};

}  // namespace voxgi::runtime
