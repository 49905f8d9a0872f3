// Sample 2: a dynamic scene through a graph file.
//
// Builds a small scene in code (a floor, a box and a point light) and gives it one animation
// that slides the box across the floor and carries the light around it. It loads a graph
// file, then for N frames steps the animation, lets the runtime upload what moved (the
// graph's passes see geometry_changed / lights_changed and redo only what depends on them),
// renders, and writes every frame as PNG plus the per-pass timings (medians over the frames)
// as a table on stdout and as JSON.
//
//   voxgi-sample-dynamic-scene [--graph graphs/default.json] [--frames 8] [--width 192]
//                              [--height 128] [--out out/dynamic]

#include <glm/gtc/constants.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>

#include "engine/image/image.hpp"
#include "engine/runtime/graph_instance.hpp"
#include "engine/runtime/runtime.hpp"
#include "engine/runtime/scene_source.hpp"
#include "engine/runtime/timings.hpp"
#include "engine/scene/scene_builder.hpp"

namespace {

using namespace voxgi;

scene::Scene moving_box_and_light() {
  scene::SceneBuilder b("moving-box");
  scene::Material floor_material;
  floor_material.name = "floor";
  floor_material.base_color = glm::vec4(0.7f, 0.7f, 0.7f, 1.0f);
  floor_material.metallic = 0.0f;
  floor_material.roughness = 0.9f;
  scene::Material box_material = floor_material;
  box_material.name = "box";
  box_material.base_color = glm::vec4(0.8f, 0.3f, 0.1f, 1.0f);
  const int floor = b.add_material(floor_material);
  const int orange = b.add_material(box_material);
  b.add_quad("floor", {-2, 0, 2}, {4, 0, 0}, {0, 0, -4}, floor);
  const int box = b.add_box("box", {0, 0, 0}, {0.5f, 0.5f, 0.5f}, orange);
  scene::Light light;
  light.name = "lamp";
  light.type = scene::LightType::Point;
  light.intensity = 8.0f;  // candela
  const int lamp = b.add_light(light, {0, 1.5f, 0});
  b.add_camera("view", {0, 2.2f, 3.5f}, {0, 0.2f, 0}, 0.8f);

  // One loop of 2 s: the box slides from x = -1 to 1 and back; the light circles it.
  scene::Animation animation;
  animation.name = "slide-and-circle";
  animation.duration = 2.0f;
  scene::AnimationChannel slide;
  slide.node = box;
  slide.path = scene::AnimationPath::Translation;
  slide.times = {0.0f, 1.0f, 2.0f};
  slide.values = {{-1, 0.25f, 0, 0}, {1, 0.25f, 0, 0}, {-1, 0.25f, 0, 0}};
  scene::AnimationChannel circle;
  circle.node = lamp;
  circle.path = scene::AnimationPath::Translation;
  for (int k = 0; k <= 8; ++k) {
    const float angle = glm::two_pi<float>() * static_cast<float>(k) / 8.0f;
    circle.times.push_back(0.25f * static_cast<float>(k));
    circle.values.emplace_back(1.2f * std::cos(angle), 1.5f, 1.2f * std::sin(angle), 0.0f);
  }
  animation.channels = {slide, circle};
  b.scene().animations.push_back(animation);
  return b.finish();
}

}  // namespace

int main(int argc, char** argv) {
  std::string graph_file = "graphs/default.json", out = "out/dynamic";
  uint32_t width = 192, height = 128;
  int frames = 8;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      if (i + 1 >= argc) throw std::invalid_argument(arg + ": expects a value");
      const std::string value = argv[++i];
      const long n = std::strtol(value.c_str(), nullptr, 10);
      if (arg == "--graph") {
        graph_file = value;
      } else if (arg == "--out") {
        out = value;
      } else if (arg == "--frames" && n >= 1 && n <= 10000) {
        frames = static_cast<int>(n);
      } else if ((arg == "--width" || arg == "--height") && n >= 1 && n <= 8192) {
        (arg == "--width" ? width : height) = static_cast<uint32_t>(n);
      } else {
        throw std::invalid_argument("bad argument '" + arg + " " + value + "'");
      }
    }

    runtime::Runtime runtime({}, moving_box_and_light());
    runtime::GraphSettings settings;
    settings.width = width;
    settings.height = height;
    runtime::GraphInstance graph(runtime, runtime::resolve_graph_path(graph_file), settings);
    const scene::Camera camera = runtime.scene().cameras.front();
    const runtime::FrameView view =
        runtime::frame_view(camera, static_cast<float>(width) / static_cast<float>(height));

    std::filesystem::create_directories(out);
    runtime::TimingsHistory timings(static_cast<size_t>(frames));
    constexpr double kFps = 30.0;
    for (int frame = 0; frame < frames; ++frame) {
      const double time = frame / kFps;
      const bool moved = runtime.animate(time);  // uploads the moved box and light
      runtime::FrameChanges changes;
      changes.camera = frame == 0;
      changes.geometry = moved;
      changes.lights = moved;
      const auto start = std::chrono::steady_clock::now();
      graph.render(view, time, changes);
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
      timings.add_frame(graph.timings(), ms);

      char name[32];
      std::snprintf(name, sizeof name, "frame-%03d.png", frame);
      image::write_png(std::filesystem::path(out) / name, graph.read("display"));
    }
    std::cout << timings.table();
    const std::filesystem::path json = std::filesystem::path(out) / "timings.json";
    timings.write_json(json,
                       {{"graph", graph_file}, {"device", runtime.context().device_summary()}});
    std::cout << "wrote " << frames << " frames and " << json.string() << " to " << out << "\n";
    // With VOXGI_VALIDATION=1 the layer watches the run; anything it says fails it.
    if (const size_t messages = runtime.context().validation_message_count()) {
      std::cerr << "voxgi-sample-dynamic-scene: error: the validation layer reported " << messages
                << " message(s)\n";
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "voxgi-sample-dynamic-scene: error: " << e.what() << "\n";
    return 1;
  }
}
