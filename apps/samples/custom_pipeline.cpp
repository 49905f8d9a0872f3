// Sample 1: a custom pipeline built in code.
//
// Builds a graph::GraphDesc in C++ from registered pass types, with no graph file: a G-buffer,
// deferred direct lighting without shadow maps, a composite and the display transform. It
// compiles the graph for a built-in scene, renders one frame headless and writes the display
// output as PNG and the linear radiance as EXR.
//
//   voxgi-sample-custom-pipeline [--scene cornell] [--width 256] [--height 256]
//                                [--out out/custom-pipeline]

#include <cstdlib>
#include <iostream>
#include <string>

#include "engine/graph/graph_desc.hpp"
#include "engine/runtime/graph_instance.hpp"
#include "engine/runtime/output_files.hpp"
#include "engine/runtime/runtime.hpp"
#include "engine/runtime/scene_source.hpp"

namespace {

using namespace voxgi;

graph::ExprField expression(const std::string& text) {
  graph::ExprField field;
  field.present = true;
  field.text = text;
  return field;
}

// A viewport-sized 2D image.
graph::ResourceDesc image(const std::string& name, const std::string& format) {
  graph::ResourceDesc resource;
  resource.name = name;
  resource.type = "image2d";
  resource.format = format;
  resource.size = {expression("viewport")};
  return resource;
}

graph::BindingDesc bind(const std::string& slot, const std::string& resource) {
  graph::BindingDesc binding;
  binding.slot = slot;
  binding.resource = resource;
  return binding;
}

graph::PassDesc pass(const std::string& name, const std::string& type,
                     std::vector<graph::BindingDesc> inputs,
                     std::vector<graph::BindingDesc> outputs) {
  graph::PassDesc p;
  p.name = name;
  p.type = type;
  p.inputs = std::move(inputs);
  p.outputs = std::move(outputs);
  return p;
}

graph::GraphDesc direct_light_only() {
  graph::GraphDesc desc;
  desc.file = "<custom_pipeline.cpp>";  // where compile errors say the graph came from
  desc.name = "direct-light-only";
  desc.resources = {
      image("base_color", "rgba8_srgb"), image("normal", "rgba16f"), image("material", "rgba8"),
      image("emission", "rgba16f"),      image("depth", "d32f"),     image("direct", "rgba16f"),
      image("hdr", "rgba16f"),           image("ldr", "rgba8")};
  desc.passes = {
      pass("gbuffer", "common.gbuffer", {},
           {bind("base_color", "base_color"), bind("normal", "normal"),
            bind("material", "material"), bind("emission", "emission"), bind("depth", "depth")}),
      pass("lighting", "common.deferred_lighting",
           {bind("base_color", "base_color"), bind("normal", "normal"),
            bind("material", "material"), bind("emission", "emission"), bind("depth", "depth")},
           {bind("radiance", "direct")}),
      pass("composite", "common.composite", {bind("direct", "direct")}, {bind("radiance", "hdr")}),
      pass("display", "common.display_transform", {bind("radiance", "hdr")},
           {bind("display", "ldr")}),
  };
  desc.outputs = {{"display", "ldr", {}}, {"linear", "hdr", {}}};
  return desc;
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene_name = "cornell", out = "out/custom-pipeline";
  uint32_t width = 256, height = 256;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      if (i + 1 >= argc) throw std::invalid_argument(arg + ": expects a value");
      const std::string value = argv[++i];
      if (arg == "--scene") {
        scene_name = value;
      } else if (arg == "--out") {
        out = value;
      } else if (arg == "--width" || arg == "--height") {
        const long n = std::strtol(value.c_str(), nullptr, 10);
        if (n < 1 || n > 8192) throw std::invalid_argument(arg + " '" + value + "': 1 to 8192");
        (arg == "--width" ? width : height) = static_cast<uint32_t>(n);
      } else {
        throw std::invalid_argument("unknown argument '" + arg + "'");
      }
    }

    runtime::Runtime runtime({}, runtime::load_scene(scene_name));
    runtime::GraphSettings settings;
    settings.width = width;
    settings.height = height;
    runtime::GraphInstance graph(runtime, direct_light_only(), settings);

    const scene::Camera camera = runtime::choose_camera(runtime.scene(), "");
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    graph.render(runtime::frame_view(camera, aspect), 0.0, {});

    for (const auto& file : runtime::write_outputs(graph, out))
      std::cout << "wrote " << file.string() << "\n";
    for (const auto& t : graph.timings())
      std::cout << t.pass << " (" << t.type << "): " << t.gpu_ms << " ms GPU\n";
    // With VOXGI_VALIDATION=1 the layer watches the run; anything it says fails it.
    if (const size_t messages = runtime.context().validation_message_count()) {
      std::cerr << "voxgi-sample-custom-pipeline: error: the validation layer reported " << messages
                << " message(s)\n";
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "voxgi-sample-custom-pipeline: error: " << e.what() << "\n";
    return 1;
  }
}
