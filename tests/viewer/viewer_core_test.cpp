// The viewer's parts that need no window or GPU: scripts, keys, the camera, image
// composition, and the runtime's file watcher, overrides, timings and slices.

#include <gtest/gtest.h>

#include <GLFW/glfw3.h>

#include <cmath>
#include <fstream>
#include <thread>

#include "apps/viewer/camera_controller.hpp"
#include "apps/viewer/image_compose.hpp"
#include "apps/viewer/script.hpp"
#include "apps/viewer/viewer_options.hpp"
#include "engine/runtime/file_watcher.hpp"
#include "engine/runtime/output_files.hpp"
#include "engine/runtime/scene_source.hpp"
#include "engine/runtime/timings.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::viewer {
namespace {

TEST(ViewerScript, ParsesCommandsArgumentsAndComments) {
  const auto commands = parse_script(
      "# a comment\nframes 3\n\nkey F2   # toggles split\nset lighting.intensity=2\ngraph 2\n"
      "screenshot out/a\nedit-check\nquit\n",
      "s.txt");
  ASSERT_EQ(commands.size(), 7u);
  EXPECT_EQ(commands[0].name, "frames");
  EXPECT_EQ(commands[0].args, std::vector<std::string>{"3"});
  EXPECT_EQ(commands[0].line, 2);
  EXPECT_EQ(commands[1].args, std::vector<std::string>{"F2"});
  EXPECT_EQ(commands[2].args, std::vector<std::string>{"lighting.intensity=2"});
  EXPECT_EQ(commands[6].name, "quit");
}

TEST(ViewerScript, NamesTheFileAndLineOfABadCommand) {
  try {
    parse_script("frames 1\njump 3\n", "session.txt");
    FAIL() << "expected a ScriptError";
  } catch (const ScriptError& e) {
    EXPECT_NE(std::string(e.what()).find("session.txt:2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("jump"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_script("frames\n", "s"), ScriptError);
  EXPECT_THROW(parse_script("key Hyper\n", "s"), ScriptError);
  EXPECT_THROW(parse_script("set nothing\n", "s"), ScriptError);
  EXPECT_THROW(load_script("/nonexistent/script.txt"), ScriptError);
}

TEST(ViewerScript, KeyNames) {
  EXPECT_EQ(key_code("w"), GLFW_KEY_W);
  EXPECT_EQ(key_code("7"), GLFW_KEY_7);
  EXPECT_EQ(key_code("F12"), GLFW_KEY_F12);
  EXPECT_EQ(key_code("tab"), GLFW_KEY_TAB);
  EXPECT_EQ(key_code("F13"), -1);
  EXPECT_EQ(key_code("F"), GLFW_KEY_F);
}

TEST(ViewerOptions, ParsesAndRejects) {
  const ViewerOptions o = parse_viewer_options({"--scene", "x.gltf", "--graph", "a.json", "--graph",
                                                "b.json", "--width", "128", "--set", "p.q=1"});
  EXPECT_EQ(o.scene, "x.gltf");
  EXPECT_EQ(o.graphs.size(), 2u);
  EXPECT_EQ(o.width, 128u);
  EXPECT_EQ(o.sets, std::vector<std::string>{"p.q=1"});
  EXPECT_EQ(parse_viewer_options({}).graphs, std::vector<std::string>{"graphs/default.json"});
  EXPECT_THROW(parse_viewer_options({"--width", "0"}), UsageError);
  EXPECT_THROW(parse_viewer_options({"--height"}), UsageError);
  EXPECT_THROW(parse_viewer_options({"--bogus"}), UsageError);
}

scene::Camera camera_at(glm::vec3 eye) {
  scene::Camera camera;
  camera.world = glm::mat4(1.0f);
  camera.world[3] = glm::vec4(eye, 1.0f);  // looking along -Z
  return camera;
}

TEST(CameraController, UntouchedReturnsTheSceneCameraExactly) {
  CameraController c;
  scene::Camera camera = camera_at({1, 2, 3});
  camera.world[0][1] = 1e-7f;  // any bit pattern must survive
  c.reset(camera, 4.0f);
  EXPECT_FALSE(c.moved());
  EXPECT_EQ(c.camera().world, camera.world);
  EXPECT_TRUE(c.take_changed());
  EXPECT_FALSE(c.take_changed());
}

TEST(CameraController, FlyMovesAlongTheViewAndOrbitKeepsTheTargetDistance) {
  CameraController c;
  c.reset(camera_at({0, 0, 5}), 2.0f);
  c.move({0, 0, 1}, 1.0f);  // forward is -Z
  EXPECT_NEAR(c.position().z, 4.0f, 1e-5f);
  EXPECT_TRUE(c.take_changed());
  const glm::mat4 world = c.camera().world;
  EXPECT_NEAR(world[3].z, 4.0f, 1e-5f);
  EXPECT_NEAR(world[2].z, 1.0f, 1e-5f);  // +Z is behind: still looking along -Z

  c.set_mode(CameraMode::Orbit);
  const glm::vec3 target = c.position() + c.forward() * 1.0f;  // distance 0.5 * extent
  c.rotate(0.7f, 0.2f);
  const glm::vec3 new_target = c.position() + c.forward() * 1.0f;
  EXPECT_NEAR(glm::length(new_target - target), 0.0f, 1e-4f);
  c.rotate(0.0f, 10.0f);  // pitch is clamped short of the pole
  EXPECT_LT(c.forward().y, 1.0f);
  EXPECT_TRUE(std::isfinite(c.forward().x));
}

image::ImageRGBA32F solid(uint32_t w, uint32_t h, float r, float g, float b) {
  image::ImageRGBA32F img(w, h);
  for (size_t i = 0; i < img.pixels.size(); i += 4) {
    img.pixels[i] = r;
    img.pixels[i + 1] = g;
    img.pixels[i + 2] = b;
    img.pixels[i + 3] = 1.0f;
  }
  return img;
}

TEST(ImageCompose, WipeTakesLeftFromAAndRightFromB) {
  const auto a = solid(4, 2, 1, 0, 0), b = solid(4, 2, 0, 0, 1);
  const auto w = wipe(a, b, 0.5f);
  EXPECT_EQ(w.at(1, 1)[0], 1.0f);
  EXPECT_EQ(w.at(2, 1)[2], 1.0f);
  EXPECT_EQ(w.at(2, 1)[0], 0.0f);
  EXPECT_THROW(wipe(a, solid(3, 2, 0, 0, 0), 0.5f), std::invalid_argument);
}

TEST(ImageCompose, InspectionFlagsBadValuesAndAppliesExposure) {
  image::ImageRGBA32F v = solid(3, 1, 0.25f, 0.25f, 0.25f);
  v.at(1, 0)[0] = NAN;
  v.at(2, 0)[1] = -1.0f;
  const auto d = inspect_to_display(v, 1.0f, true, Channels::RGB);
  EXPECT_FLOAT_EQ(d.at(0, 0)[0], 0.5f);  // display-referred: × 2
  EXPECT_EQ(d.at(1, 0)[0], 1.0f);        // NaN: magenta
  EXPECT_EQ(d.at(1, 0)[1], 0.0f);
  EXPECT_EQ(d.at(2, 0)[0], 0.0f);  // negative: cyan
  EXPECT_EQ(d.at(2, 0)[1], 1.0f);
  const auto linear =
      inspect_to_display(solid(1, 1, 0.0031308f, 1.0f, 0.5f), 0.0f, false, Channels::G);
  EXPECT_NEAR(linear.at(0, 0)[0], 1.0f, 1e-5f);  // G shown as grey, sRGB-encoded
}

TEST(ImageCompose, FitNearestScalesUpAndDownKeepingTheAspect) {
  image::ImageRGBA32F small = solid(2, 1, 0, 0, 0);
  small.at(1, 0)[0] = 1.0f;
  const auto up = fit_nearest(small, 8, 8);  // ×4: 8×4, the rest black
  EXPECT_EQ(up.at(3, 3)[0], 0.0f);
  EXPECT_EQ(up.at(4, 3)[0], 1.0f);
  EXPECT_EQ(up.at(4, 4)[0], 0.0f);
  const auto down = fit_nearest(solid(64, 64, 0.5f, 0.5f, 0.5f), 8, 4);
  EXPECT_EQ(down.at(3, 3)[0], 0.5f);
  EXPECT_EQ(down.at(4, 0)[0], 0.0f);
}

TEST(ImageCompose, PacksBytesInSwapchainOrder) {
  const auto img = solid(1, 1, 1.0f, 0.5f, 0.0f);
  EXPECT_EQ(pack_rgba8(img, false), (std::vector<uint8_t>{255, 128, 0, 255}));
  EXPECT_EQ(pack_rgba8(img, true), (std::vector<uint8_t>{0, 128, 255, 255}));
}

TEST(Runtime, OverridesAndGraphPaths) {
  const auto o = runtime::parse_overrides({"a.b=1", "c=x=y"});
  EXPECT_EQ(o.at("a.b"), "1");
  EXPECT_EQ(o.at("c"), "x=y");
  EXPECT_THROW(runtime::parse_overrides({"novalue"}), std::invalid_argument);
  EXPECT_THROW(runtime::parse_overrides({"=1"}), std::invalid_argument);
  EXPECT_TRUE(std::filesystem::exists(runtime::resolve_graph_path("graphs/default.json")));
}

TEST(Runtime, FileWatcherSeesEditsAppearancesAndRemovals) {
  const auto dir = test::make_temp_dir("voxgi-watch");
  const auto file = dir / "graph.json";
  const auto later = dir / "later.json";
  std::filesystem::create_directories(dir / "tree");
  { std::ofstream(file) << "one"; }
  runtime::FileWatcher watcher;
  watcher.watch_file(file);
  watcher.watch_file(later);
  watcher.watch_tree(dir / "tree");
  EXPECT_TRUE(watcher.poll().empty());
  { std::ofstream(file) << "two, longer"; }
  EXPECT_EQ(watcher.poll(), std::vector<std::filesystem::path>{file});
  EXPECT_TRUE(watcher.poll().empty());
  { std::ofstream(later) << "x"; }
  { std::ofstream(dir / "tree" / "a.comp") << "x"; }
  EXPECT_EQ(watcher.poll().size(), 2u);
  std::filesystem::remove(dir / "tree" / "a.comp");
  EXPECT_EQ(watcher.poll(), std::vector<std::filesystem::path>{dir / "tree" / "a.comp"});
  runtime::FileWatcher missing;
  missing.watch_tree(dir / "no-such-folder");
  EXPECT_TRUE(missing.poll().empty());
}

TEST(Runtime, TimingsMediansSkipsAndJson) {
  runtime::TimingsHistory history(3);
  for (double gpu : {1.0, 5.0, 3.0, 2.0}) {
    std::vector<graph::Executor::PassTiming> frame(2);
    frame[0] = {"a", "t.a", gpu, 0.1, ""};
    frame[1] = {"b", "t.b", 0.0, 0.0, gpu > 2.5 ? "unchanged" : ""};
    history.add_frame(frame, gpu * 2);
  }
  EXPECT_EQ(history.frames(), 3u);  // the window drops the first frame
  const auto summary = history.summary();
  ASSERT_EQ(summary.size(), 2u);
  EXPECT_DOUBLE_EQ(summary[0].gpu_ms_median, 3.0);  // of 5, 3, 2
  EXPECT_EQ(summary[1].skipped, 2u);
  EXPECT_EQ(summary[1].skip_reason, "unchanged");
  EXPECT_EQ(history.gpu_totals_ms(), (std::vector<float>{5.0f, 3.0f, 2.0f}));
  EXPECT_NE(history.table().find("t.a"), std::string::npos);
  const std::string json = history.json({{"graph", "g.json"}});
  EXPECT_NE(json.find("\"graph\": \"g.json\""), std::string::npos) << json;
  EXPECT_THROW(history.write_json("/nonexistent/dir/t.json"), std::runtime_error);
}

TEST(Runtime, SlicesOfVolumesAndClipmaps) {
  graph::ResourceInfo clipmap;
  clipmap.name = "radiance";
  clipmap.kind = graph::ResourceKind::Clipmap;
  clipmap.extent = {2, 2, 6};  // 3 levels of 2³
  clipmap.clipmap_levels = 3;
  std::vector<float> texels(2 * 2 * 6 * 4);
  for (size_t i = 0; i < texels.size(); ++i) texels[i] = static_cast<float>(i / 16);  // z
  EXPECT_EQ(runtime::level_count(clipmap), 3u);
  EXPECT_EQ(runtime::slice_count(clipmap), 2u);
  EXPECT_EQ(runtime::slice_of(clipmap, texels, 2, 1).at(1, 1)[0], 5.0f);
  EXPECT_EQ(runtime::slice_of(clipmap, texels, 1, 0).at(0, 0)[0], 2.0f);
  EXPECT_EQ(runtime::slice_of(clipmap, texels, 9, 9).at(0, 0)[0], 5.0f);  // clamped
  texels.resize(10);
  EXPECT_THROW(runtime::slice_of(clipmap, texels, 0, 0), std::invalid_argument);

  const auto d = runtime::difference(solid(2, 1, 1, 1, 1), solid(2, 1, 0.5f, 1, 1), 2.0f);
  EXPECT_FLOAT_EQ(d.at(0, 0)[0], 1.0f);
  EXPECT_FLOAT_EQ(runtime::difference_stats(solid(2, 1, 1, 1, 1), solid(2, 1, 0.5f, 1, 1)).max_abs,
                  0.5f);
}

}  // namespace
}  // namespace voxgi::viewer
