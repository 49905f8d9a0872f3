// Soak: the built-in Cornell box with its tall block sliding and its light circling, rendered
// for many frames through every shipped graph at a small size, with the validation layer on.
// Each graph must record no validation message and no NaN, Inf or negative pixel, and after
// the warm-up neither the device memory the allocator holds nor the process's resident host
// memory may grow (bounds below).

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "engine/runtime/graph_instance.hpp"
#include "engine/runtime/runtime.hpp"
#include "engine/scene/builtin_scenes.hpp"

namespace voxgi::test {
namespace {

constexpr int kWarmupFrames = 8;
constexpr int kFrames = 32;
// Host memory may move by allocator noise and caches filled on first use, not by a leak per
// frame: the 24 frames after the warm-up leaking even 1 MiB each would exceed it (measured
// +0.0 to +0.6 MiB over the graphs on lavapipe).
constexpr double kHostGrowthBoundMiB = 16.0;

// Resident set size of this process (MiB), from /proc/self/statm.
double resident_mib() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) /
         (1024.0 * 1024.0);
}

// The Cornell box with an animation: the tall block slides 20 cm and back, the light circles.
scene::Scene moving_cornell() {
  scene::Scene scene = scene::make_builtin_scene("cornell");
  int block = -1;
  for (size_t i = 0; i < scene.nodes.size(); ++i) {
    if (scene.nodes[i].name == "tall_block") block = static_cast<int>(i);
  }
  if (block < 0 || scene.lights.empty() || scene.lights[0].node < 0) return scene;
  const glm::vec3 at = scene.nodes[size_t(block)].translation;
  const glm::vec3 lamp = scene.nodes[size_t(scene.lights[0].node)].translation;
  scene::Animation animation;
  animation.name = "soak";
  animation.duration = 1.0f;
  scene::AnimationChannel slide;
  slide.node = block;
  slide.path = scene::AnimationPath::Translation;
  slide.times = {0.0f, 0.5f, 1.0f};
  slide.values = {glm::vec4(at, 0.0f), glm::vec4(at + glm::vec3(0.2f, 0.0f, 0.0f), 0.0f),
                  glm::vec4(at, 0.0f)};
  scene::AnimationChannel circle;
  circle.node = scene.lights[0].node;
  circle.path = scene::AnimationPath::Translation;
  for (int k = 0; k <= 8; ++k) {
    const float angle = 6.2831853f * static_cast<float>(k) / 8.0f;
    circle.times.push_back(0.125f * static_cast<float>(k));
    circle.values.emplace_back(
        lamp + glm::vec3(0.1f * std::cos(angle), 0.0f, 0.1f * std::sin(angle)), 0.0f);
  }
  animation.channels = {slide, circle};
  scene.animations.push_back(animation);
  return scene;
}

class Soak : public ::testing::TestWithParam<const char*> {};

TEST_P(Soak, ManyFramesStayFiniteValidAndFlatInMemory) {
  runtime::RuntimeOptions options;
  options.validation = true;
  runtime::Runtime runtime(options, moving_cornell());
  ASSERT_FALSE(runtime.scene().animations.empty()) << "the Cornell box changed its node names";
  runtime::GraphSettings settings;
  // The gathers' cost grows with the pixels and the clipmap's levels, a leak or a validation
  // message does not: two levels keep the paths between a finer level and the coarser one it
  // covers.
  settings.width = 16;
  settings.height = 16;
  settings.overrides = {{"voxel.resolution", "32"}, {"voxel.levels", "2"}};
  // "lpv.json octree": the graph file and its octree LPV.
  const std::string param = GetParam();
  const std::string name = param.substr(0, param.find(' '));
  const std::string graph = std::string(VOXGI_SOURCE_DIR) + "/graphs/" + name;
  if (name != "vct.json" && name != "dvs.json" && name != "lpv.json") {
    settings.overrides.clear();
  }
  // Every moving frame propagates again: a few iterations keep lavapipe fast.
  if (name == "lpv.json") settings.overrides["lpv.iterations"] = "8";
  if (param == "lpv.json octree") {
    settings.overrides["lpv.octree_levels"] = "5";
    settings.overrides["lpv.iterations"] = "4";
  }
  runtime::GraphInstance instance(runtime, graph, settings);
  const runtime::FrameView view = runtime::frame_view(runtime.scene().cameras.front(), 1.0f);
  int moved_frames = 0;
  double host_after_warmup = 0.0;
  uint64_t device_after_warmup = 0;
  for (int frame = 0; frame < kFrames; ++frame) {
    const double time = frame / 30.0;
    runtime::FrameChanges changes;
    changes.camera = frame == 0;
    changes.geometry = changes.lights = runtime.animate(time);
    moved_frames += changes.geometry ? 1 : 0;
    instance.render(view, time, changes);
    if (frame % 8 == 7) {
      const image::ImageRGBA32F linear = instance.read("linear");
      size_t bad = 0;
      for (float v : linear.pixels) bad += !(std::isfinite(v) && v >= 0.0f);
      ASSERT_EQ(bad, 0u) << GetParam() << ": frame " << frame;
    }
    if (frame == kWarmupFrames - 1) {
      host_after_warmup = resident_mib();
      device_after_warmup = runtime.context().allocator().bytes_in_use();
    }
  }
  const double host_growth = resident_mib() - host_after_warmup;
  const uint64_t device_end = runtime.context().allocator().bytes_in_use();
  std::printf(
      "[soak] %s: %d frames, device memory %.2f MiB (after warm-up %.2f), host memory "
      "%+.2f MiB after warm-up\n",
      GetParam(), kFrames, device_end / 1048576.0, device_after_warmup / 1048576.0, host_growth);
  EXPECT_GT(moved_frames, kFrames / 2) << "the scene did not move";
  EXPECT_EQ(device_end, device_after_warmup) << GetParam();
  EXPECT_LT(host_growth, kHostGrowthBoundMiB) << GetParam();
  EXPECT_EQ(runtime.context().validation_message_count(), 0u) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Graphs, Soak,
                         ::testing::Values("default.json", "vct.json", "dvs.json", "lpv.json",
                                           "lpv.json octree", "reference.json"),
                         [](const auto& param_info) {
                           std::string name = param_info.param;
                           const bool octree = name.ends_with(" octree");
                           return name.substr(0, name.find('.')) + (octree ? "_octree" : "");
                         });

}  // namespace
}  // namespace voxgi::test
