#include "engine/runtime/graph_instance.hpp"

#include "engine/runtime/runtime.hpp"

namespace voxgi::runtime {

GraphInstance::GraphInstance(Runtime& runtime, const std::filesystem::path& graph_file,
                             GraphSettings settings)
    : GraphInstance(runtime, graph::load_graph_file(graph_file), std::move(settings)) {}

GraphInstance::GraphInstance(Runtime& runtime, graph::GraphDesc desc, GraphSettings settings)
    : runtime_(runtime), desc_(std::move(desc)), settings_(std::move(settings)) {
  runtime_.load_plugins_for(desc_);  // extra outputs name resources, never other families
  executor_ = std::make_unique<graph::Executor>(runtime_.context(), runtime_.shaders(),
                                                runtime_.registry());
  executor_->build(compile(settings_), runtime_.scene(), runtime_.gpu_scene());
  frames_ = std::make_unique<FrameDriver>(*executor_);
}

graph::CompiledGraph GraphInstance::compile(const GraphSettings& settings) const {
  graph::GraphDesc compiled_desc = desc_;
  for (const auto& [name, resource] : settings.extra_outputs) {
    graph::OutputDesc output;
    output.name = name;
    output.resource = resource;
    compiled_desc.outputs.push_back(output);
  }
  graph::CompileOptions options;
  options.viewport_width = settings.width;
  options.viewport_height = settings.height;
  options.scene_features = runtime_.scene().features().as_map();
  graph::use_device(options, runtime_.context());
  options.overrides = settings.overrides;
  options.full_barriers = settings.full_barriers;
  options.alias_transients = settings.alias_transients;
  return graph::compile(compiled_desc, runtime_.registry(), options);
}

GraphInstance::~GraphInstance() = default;

void GraphInstance::render(const FrameView& view, double time, const FrameChanges& changes) {
  frames_->render(view, time, changes);
}

image::ImageRGBA32F GraphInstance::read(const std::string& output) {
  image::ImageRGBA32F picture;
  picture.pixels = executor_->read_output(output, picture.width, picture.height);
  // Volumes come back whole (all slices), layered images as layer 0; see slice_of().
  return picture;
}

bool GraphInstance::has_output(const std::string& output) const {
  return executor_->compiled().outputs.count(output) > 0;
}

const std::vector<graph::Executor::PassTiming>& GraphInstance::timings() const {
  return executor_->timings();
}

bool GraphInstance::set_param(const std::string& key, const std::string& value) {
  try {
    const bool live = executor_->set_param(key, value);
    settings_.overrides[key] = value;
    return live;
  } catch (const graph::ParamNeedsRecompile&) {
    // The parameter sizes resources: compile again; the executor keeps the persistent
    // resources whose description did not change. A failed compile changes nothing.
    GraphSettings changed = settings_;
    changed.overrides[key] = value;
    graph::CompiledGraph compiled = compile(changed);
    executor_->build(compiled, runtime_.scene(), runtime_.gpu_scene());
    settings_ = std::move(changed);
    frames_->restart();  // the next frame recomputes what the new sizes invalidated
    return false;
  }
}

const graph::ParamValue* GraphInstance::param(const std::string& pass,
                                              const std::string& name) const {
  const graph::CompiledPass* compiled_pass = executor_->compiled().find_pass(pass);
  if (!compiled_pass) return nullptr;
  auto it = compiled_pass->params.find(name);
  return it == compiled_pass->params.end() ? nullptr : &it->second;
}

const graph::CompiledGraph& GraphInstance::compiled() const {
  return executor_->compiled();
}

}  // namespace voxgi::runtime
