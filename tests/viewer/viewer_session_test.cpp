// The viewer as a user runs it: a window on a private Xvfb display, driven by a script.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <thread>

#include "engine/image/image.hpp"
#include "tests/apps/child_process.hpp"
#include "tests/gpu/gpu_test_env.hpp"
#include "tests/viewer/viewer_test_support.hpp"
#include "tests/viewer/xvfb_display.hpp"

namespace voxgi::test {
namespace {

namespace fs = std::filesystem;

class ViewerSessionTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { xvfb_ = std::make_unique<XvfbDisplay>(); }
  static void TearDownTestSuite() { xvfb_.reset(); }

  void SetUp() override {
    if (!xvfb_->installed()) {
      if (running_in_ci()) FAIL() << "Xvfb is not installed (needed under CI=true): install xvfb";
      GTEST_SKIP() << "Xvfb is not installed: install xvfb to run the viewer tests";
    }
    ASSERT_TRUE(xvfb_->running()) << xvfb_->error();
    dir_ = make_temp_dir("voxgi-viewer-test");
  }

  ProcessOptions options() const {
    ProcessOptions o;
    o.working_dir = dir_;
    o.env["DISPLAY"] = xvfb_->display();
    o.env["WAYLAND_DISPLAY"] = std::nullopt;
    if (!std::getenv("XDG_RUNTIME_DIR")) o.env["XDG_RUNTIME_DIR"] = "/tmp";
    o.timeout = std::chrono::milliseconds(120000);
    return o;
  }

  ProcessResult viewer(const std::vector<std::string>& args) const {
    std::vector<std::string> all = {"--validation", "--width", "96", "--height", "96"};
    all.insert(all.end(), args.begin(), args.end());
    return run_process(VOXGI_VIEWER_EXE, all, options());
  }

  static image::ImageRGBA32F png(const fs::path& file) { return image::read_png(file); }

  static std::unique_ptr<XvfbDisplay> xvfb_;
  fs::path dir_;
};

std::unique_ptr<XvfbDisplay> ViewerSessionTest::xvfb_;

TEST_F(ViewerSessionTest, ScriptedSessionSwitchesGraphsEditsParametersAndTakesScreenshots) {
  write_file(dir_ / "a.json", test_graph_text(0.05));
  write_file(dir_ / "b.json", test_graph_text(0.4));
  write_file(dir_ / "session.txt", R"(# keys, a parameter, a graph switch, split view, screenshots
frames 2
screenshot shots/start
set ambient.radiance=0.2
screenshot shots/param
key 2
screenshot shots/switched
key Tab
key W
screenshot shots/moved
light 0 intensity 0
screenshot shots/unlit
light 0 intensity 1
key F2
wipe 0.5
screenshot shots/split
diff on 8
screenshot shots/difference
diff off
key F2
timings shots/timings.json
inspect gbuffer.normal
exposure 0
screenshot shots/normals
inspect off
window 700 500
frames 2
window-shot shots/window.png
quit
)");
  const ProcessResult run =
      viewer({"--graph", "a.json", "--graph", "b.json", "--script", "session.txt"});
  ASSERT_EQ(run.exit_code, 0) << run.describe();
  EXPECT_EQ(run.err.find("vulkan validation"), std::string::npos) << run.err;

  const fs::path shots = dir_ / "shots";
  for (const char* name :
       {"start", "param", "switched", "moved", "unlit", "split", "difference", "normals"}) {
    ASSERT_TRUE(fs::exists(shots / (std::string(name) + ".png"))) << name << "\n" << run.err;
    ASSERT_TRUE(fs::exists(shots / (std::string(name) + ".exr"))) << name;
  }
  const image::ImageRGBA32F start = png(shots / "start.png");
  const image::ImageRGBA32F param = png(shots / "param.png");
  const image::ImageRGBA32F switched = png(shots / "switched.png");
  const image::ImageRGBA32F moved = png(shots / "moved.png");
  const image::ImageRGBA32F split = png(shots / "split.png");
  const image::ImageRGBA32F difference = png(shots / "difference.png");
  const image::ImageRGBA32F normals = png(shots / "normals.png");
  EXPECT_EQ(start.width, 96u);
  EXPECT_EQ(start.height, 96u);
  EXPECT_GT(distinct_colors(start), 50u) << "the first screenshot looks blank";
  // More ambient light brightens the frame; graph B (ambient 0.4) differs from A at 0.2.
  EXPECT_GT(compare_images(start, param).mean_abs, 0.02);
  EXPECT_GT(compare_images(param, switched).mean_abs, 0.02);
  EXPECT_GT(compare_images(param, moved).mean_abs, 0.005) << "the W key did not move the camera";
  EXPECT_LT(mean_rgb(png(shots / "unlit.png")), mean_rgb(moved) - 0.02)
      << "switching the light off should darken the frame";
  // The split shows A on the left and B on the right.
  EXPECT_GT(compare_images(moved, split).max_abs, 0.05);
  EXPECT_GT(distinct_colors(difference), 2u);
  EXPECT_GT(compare_images(moved, normals).mean_abs, 0.02);

  std::ifstream timings_file(shots / "timings.json");
  const nlohmann::json timings = nlohmann::json::parse(timings_file);
  ASSERT_TRUE(timings.contains("passes"));
  std::vector<std::string> passes;
  for (const auto& p : timings["passes"]) passes.push_back(p["pass"].get<std::string>());
  EXPECT_NE(std::find(passes.begin(), passes.end(), "lighting"), passes.end());

  const image::ImageRGBA32F window = png(shots / "window.png");
  EXPECT_EQ(window.width, 700u) << "the swapchain should follow the resized window";
  EXPECT_EQ(window.height, 500u);
}

// Variants of one file: a slot starts on one (FILE#VARIANT), V cycles them, the script picks
// one; a parameter that sizes resources (the shadow maps' resolution) recompiles the graph.
TEST_F(ViewerSessionTest, VariantsSwitchAndSizingParametersRecompile) {
  write_file(dir_ / "graph.json", test_graph_text(0.05));
  write_file(dir_ / "session.txt", R"(frames 2
screenshot shots/bright
key V
frames 1
screenshot shots/small_shadows
key V
frames 1
screenshot shots/plain
variant bright
set shadows.resolution=128
frames 2
screenshot shots/bright_resized
set shadows.resolution=256
variant none
frames 1
screenshot shots/plain_again
quit
)");
  const ProcessResult run = viewer({"--graph", "graph.json#bright", "--script", "session.txt"});
  ASSERT_EQ(run.exit_code, 0) << run.describe();
  EXPECT_EQ(run.err.find("vulkan validation"), std::string::npos) << run.err;
  const fs::path shots = dir_ / "shots";
  const image::ImageRGBA32F bright = png(shots / "bright.png");
  const image::ImageRGBA32F plain = png(shots / "plain.png");
  // The variant's ambient light (0.6) against the file's (0.05).
  EXPECT_GT(mean_rgb(bright), mean_rgb(plain) + 0.05);
  // 64-texel shadow maps change the shadows only: close to the plain frame, not identical.
  const image::ImageRGBA32F small = png(shots / "small_shadows.png");
  EXPECT_GT(compare_images(plain, small).max_abs, 0.0);
  EXPECT_LT(compare_images(plain, small).mean_abs, 0.05);
  // Resized shadow maps keep the variant; the file as written comes back exactly.
  EXPECT_GT(mean_rgb(png(shots / "bright_resized.png")), mean_rgb(plain) + 0.05);
  EXPECT_LT(compare_images(plain, png(shots / "plain_again.png")).max_abs, 1e-6);
  EXPECT_NE(run.err.find("graph.json #small_shadows"), std::string::npos) << run.err;
}

// Split view of two variants of one file runs them as one graph: the passes they share
// (G-buffer, shadows, direct light) once, B's ambient and what follows apart. Each half of the
// split frame is what the variant shows alone, and the timings name the shared passes.
TEST_F(ViewerSessionTest, SplitViewOfTwoVariantsRunsSharedPassesOnce) {
  write_file(dir_ / "graph.json", test_graph_text(0.05));
  write_file(dir_ / "session.txt", R"(frames 2
screenshot shots/a
key 2
frames 2
screenshot shots/b
key 1
split on
wipe 0.5
frames 2
screenshot shots/split
timings shots/pair.json
set ambient.radiance=0.3
frames 1
screenshot shots/live
set lighting.pcf_radius=2
frames 1
timings shots/remerged.json
split off
frames 1
timings shots/alone.json
quit
)");
  const ProcessResult run =
      viewer({"--graph", "graph.json", "--graph", "graph.json#bright", "--script", "session.txt"});
  ASSERT_EQ(run.exit_code, 0) << run.describe();
  EXPECT_EQ(run.err.find("vulkan validation"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("shared passes run once"), std::string::npos) << run.err;
  const fs::path shots = dir_ / "shots";
  const image::ImageRGBA32F a = png(shots / "a.png");
  const image::ImageRGBA32F b = png(shots / "b.png");
  const image::ImageRGBA32F split = png(shots / "split.png");
  ASSERT_EQ(split.width, a.width);
  float left = 0.0f, right = 0.0f;
  for (uint32_t y = 0; y < split.height; ++y) {
    for (uint32_t x = 0; x < split.width; ++x) {
      for (uint32_t c = 0; c < 3; ++c) {
        const size_t i = (size_t(y) * split.width + x) * 4 + c;
        if (x < split.width * 4 / 10)
          left = std::max(left, std::abs(split.pixels[i] - a.pixels[i]));
        if (x > split.width * 6 / 10)
          right = std::max(right, std::abs(split.pixels[i] - b.pixels[i]));
      }
    }
  }
  EXPECT_LE(left, 1.5f / 255.0f) << "the left half is A alone";
  EXPECT_LE(right, 1.5f / 255.0f) << "the right half is B alone";

  std::ifstream pair_file(shots / "pair.json");
  const nlohmann::json pair = nlohmann::json::parse(pair_file);
  const std::string shared = pair["shared_passes"].get<std::string>();
  for (const char* pass : {"gbuffer", "shadows", "lighting"}) {
    EXPECT_NE(shared.find(pass), std::string::npos) << shared;
  }
  EXPECT_EQ(shared.find("ambient"), std::string::npos) << shared;
  std::vector<std::string> passes;
  for (const auto& p : pair["passes"]) passes.push_back(p["pass"].get<std::string>());
  EXPECT_EQ(std::count(passes.begin(), passes.end(), "gbuffer"), 1);
  EXPECT_EQ(std::count(passes.begin(), passes.end(), "b/ambient"), 1);
  EXPECT_EQ(std::count(passes.begin(), passes.end(), "b/gbuffer"), 0);
  // An edit of A's own ambient pass applies to the pair live (A's half brightens, no new
  // merge); an edit of a shared pass (lighting) makes the two differ there: merged again, with
  // lighting and what follows run apart.
  const auto count = [&](const std::string& text) {
    size_t n = 0;
    for (size_t at = run.err.find(text); at != std::string::npos; at = run.err.find(text, at + 1))
      ++n;
    return n;
  };
  EXPECT_EQ(count("shared passes run once"), 2u) << run.err;
  EXPECT_GT(mean_rgb(png(shots / "live.png")), mean_rgb(split) + 0.02);
  std::ifstream remerged_file(shots / "remerged.json");
  const std::string remerged =
      nlohmann::json::parse(remerged_file)["shared_passes"].get<std::string>();
  EXPECT_NE(remerged.find("gbuffer"), std::string::npos) << remerged;
  EXPECT_EQ(remerged.find("lighting"), std::string::npos) << remerged;
  // Split off: the active graph alone again.
  std::ifstream alone_file(shots / "alone.json");
  EXPECT_FALSE(nlohmann::json::parse(alone_file).contains("shared_passes"));
}

TEST_F(ViewerSessionTest, ScreenshotMatchesVoxgiRenderOfTheSameFrame) {
  write_file(dir_ / "graph.json", test_graph_text(0.05));
  write_file(dir_ / "session.txt", "frames 3\nscreenshot viewer\nquit\n");
  const ProcessResult run = viewer({"--graph", "graph.json", "--script", "session.txt"});
  ASSERT_EQ(run.exit_code, 0) << run.describe();

  ProcessOptions render_options = options();
  const ProcessResult render = run_process(VOXGI_EXE,
                                           {"render", "--graph", "graph.json", "--width", "96",
                                            "--height", "96", "--frames", "3", "--out", "render"},
                                           render_options);
  ASSERT_EQ(render.exit_code, 0) << render.describe();

  // The screenshot is the viewer's image area without the UI.
  const ImageDifference display =
      compare_images(png(dir_ / "viewer.png"), png(dir_ / "render.png"));
  EXPECT_LE(display.max_abs, 2.0 / 255.0);
  const ImageDifference linear =
      compare_images(image::read_exr(dir_ / "viewer.exr"), image::read_exr(dir_ / "render.exr"));
  EXPECT_LE(linear.max_abs, 1e-3);
  std::cout << "viewer screenshot vs voxgi render: display max " << display.max_abs * 255.0
            << "/255, linear max " << linear.max_abs << "\n";
}

TEST_F(ViewerSessionTest, GltfCamerasAreSelectableAndMatchVoxgiRender) {
  const fs::path scene = fs::path(VOXGI_SHARED_DIR) / "scenes/cornell-box/cornell-box.gltf";
  if (!fs::exists(scene)) GTEST_SKIP() << "shared scenes are absent: " << scene;
  write_file(dir_ / "graph.json", test_graph_text(0.05));
  write_file(dir_ / "session.txt",
             "frames 1\ncamera fly\nmove 0.3 0 0\nscreenshot moved\ncamera cornell_camera\n"
             "frames 2\nscreenshot chosen\nquit\n");
  const ProcessResult run =
      viewer({"--scene", scene.string(), "--graph", "graph.json", "--script", "session.txt"});
  ASSERT_EQ(run.exit_code, 0) << run.describe();
  const ProcessResult render = run_process(
      VOXGI_EXE,
      {"render", "--scene", scene.string(), "--camera", "cornell_camera", "--graph", "graph.json",
       "--width", "96", "--height", "96", "--frames", "3", "--out", "render"},
      options());
  ASSERT_EQ(render.exit_code, 0) << render.describe();
  EXPECT_LE(compare_images(png(dir_ / "chosen.png"), png(dir_ / "render.png")).max_abs,
            2.0 / 255.0);
  EXPECT_GT(compare_images(png(dir_ / "moved.png"), png(dir_ / "render.png")).mean_abs, 0.005);

  write_file(dir_ / "bad-camera.txt", "camera nobody\n");
  const ProcessResult bad =
      viewer({"--scene", scene.string(), "--graph", "graph.json", "--script", "bad-camera.txt"});
  EXPECT_EQ(bad.exit_code, 1) << bad.describe();
  EXPECT_NE(bad.err.find("cornell_camera"), std::string::npos) << "lists the cameras\n" << bad.err;
}

TEST_F(ViewerSessionTest, AnimationsPauseStepAndPlay) {
  write_file(dir_ / "slide.gltf", animated_gltf_text());
  write_file(dir_ / "graph.json", test_graph_text(0.05));
  write_file(dir_ / "session.txt", R"(camera overview
frames 2
screenshot t0
frames 2
screenshot t0-paused
step 6
screenshot t1
play
frames 3
screenshot t2
pause
light 0 color 1 0.2 0.2
light 0 position 0 1.2 0
screenshot lit-red
quit
)");
  const ProcessResult run =
      viewer({"--scene", "slide.gltf", "--graph", "graph.json", "--script", "session.txt"});
  ASSERT_EQ(run.exit_code, 0) << run.describe();
  EXPECT_EQ(run.err.find("vulkan validation"), std::string::npos) << run.err;
  const image::ImageRGBA32F t0 = png(dir_ / "t0.png");
  EXPECT_GT(distinct_colors(t0), 20u);
  EXPECT_EQ(compare_images(t0, png(dir_ / "t0-paused.png")).max_abs, 0.0) << "paused time moved";
  const image::ImageRGBA32F t1 = png(dir_ / "t1.png");
  const image::ImageRGBA32F t2 = png(dir_ / "t2.png");
  EXPECT_GT(compare_images(t0, t1).mean_abs, 1e-3) << "stepping should move the quad";
  EXPECT_GT(compare_images(t1, t2).mean_abs, 1e-3) << "playing should move the quad";
  // A red light: the red channel dominates.
  const image::ImageRGBA32F red = png(dir_ / "lit-red.png");
  double r = 0.0, g = 0.0;
  for (size_t i = 0; i < red.pixels.size(); i += 4) {
    r += red.pixels[i];
    g += red.pixels[i + 1];
  }
  EXPECT_GT(r, 1.5 * g);
}

TEST_F(ViewerSessionTest, HotReloadPicksUpEditsAndKeepsTheLastGoodGraphOnErrors) {
  const fs::path graph = dir_ / "live.json";
  write_file(graph, test_graph_text(0.05));
  write_file(dir_ / "session.txt", R"(frames 2
screenshot before
wait-for edited 60
edit-check
screenshot after-edit
wait-for broken 60
edit-check
frames 2
screenshot after-error
quit
)");
  ProcessResult run;
  std::thread session([&] { run = viewer({"--graph", "live.json", "--script", "session.txt"}); });
  const bool before = wait_for_file(dir_ / "before.png", 90);
  if (before) {
    replace_file(graph, test_graph_text(0.5));
    write_file(dir_ / "edited", "");
  }
  const bool after_edit = before && wait_for_file(dir_ / "after-edit.png", 90);
  if (after_edit) {
    replace_file(graph, "{ \"name\": \"broken\", \"passes\": [ { \"name\": 3 } ] ");
    write_file(dir_ / "broken", "");
  }
  session.join();
  ASSERT_TRUE(before && after_edit) << run.describe();
  ASSERT_EQ(run.exit_code, 0) << run.describe();
  EXPECT_EQ(run.err.find("vulkan validation"), std::string::npos) << run.err;

  const image::ImageRGBA32F a = png(dir_ / "before.png");
  const image::ImageRGBA32F b = png(dir_ / "after-edit.png");
  const image::ImageRGBA32F c = png(dir_ / "after-error.png");
  EXPECT_GT(compare_images(a, b).mean_abs, 0.02) << "the edit did not show";
  EXPECT_EQ(compare_images(b, c).max_abs, 0.0) << "the last good graph should keep running";
  // The error names the file and says the last good version keeps running.
  EXPECT_NE(run.err.find("live.json"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("error"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("last good"), std::string::npos) << run.err;
}

TEST_F(ViewerSessionTest, ShaderEditsRecompileAndShaderErrorsKeepTheLastGoodBuild) {
  // A private copy of the shader tree, so the edits touch nothing shared.
  const fs::path shaders = dir_ / "shaders";
  fs::copy(fs::path(VOXGI_SOURCE_DIR) / "shaders", shaders, fs::copy_options::recursive);
  const fs::path ambient = shaders / "common" / "ambient.comp";
  std::string source;
  {
    std::ifstream in(ambient);
    std::stringstream text;
    text << in.rdbuf();
    source = text.str();
  }
  write_file(dir_ / "graph.json", test_graph_text(0.05));
  write_file(dir_ / "session.txt", R"(frames 2
screenshot before
wait-for touched 60
edit-check
screenshot after-touch
wait-for broken 60
edit-check
frames 2
screenshot after-error
quit
)");
  ProcessOptions o = options();
  o.env["VOXGI_SHADER_DIR"] = shaders.string();
  o.env["VOXGI_SHADER_CACHE"] = (dir_ / "spirv-cache").string();
  ProcessResult run;
  std::thread session([&] {
    run = run_process(VOXGI_VIEWER_EXE,
                      {"--validation", "--width", "96", "--height", "96", "--graph", "graph.json",
                       "--script", "session.txt"},
                      o);
  });
  const bool before = wait_for_file(dir_ / "before.png", 90);
  if (before) {
    replace_file(ambient, source + "\n// an edit that changes nothing\n");
    write_file(dir_ / "touched", "");
  }
  const bool touched = before && wait_for_file(dir_ / "after-touch.png", 90);
  if (touched) {
    replace_file(ambient, source + "\nthis is not GLSL;\n");
    write_file(dir_ / "broken", "");
  }
  session.join();
  ASSERT_TRUE(before && touched) << run.describe();
  ASSERT_EQ(run.exit_code, 0) << run.describe();
  EXPECT_NE(run.err.find("reloaded"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("ambient.comp"), std::string::npos) << "the shader error names the file\n"
                                                             << run.err;
  EXPECT_EQ(compare_images(png(dir_ / "before.png"), png(dir_ / "after-touch.png")).max_abs, 0.0);
  EXPECT_EQ(compare_images(png(dir_ / "before.png"), png(dir_ / "after-error.png")).max_abs, 0.0);
}

TEST_F(ViewerSessionTest, BadInputGivesAMessageAndANonZeroExit) {
  write_file(dir_ / "graph.json", test_graph_text(0.05));
  write_file(dir_ / "bad-graph.json",
             "{ \"passes\": [ { \"name\": \"x\", \"type\": \"common.nope\" } ] }");
  write_file(dir_ / "bad-script.txt", "frames 1\nfly-to-the-moon\n");

  ProcessResult r = viewer({"--scene", "missing.gltf", "--graph", "graph.json"});
  EXPECT_EQ(r.exit_code, 1) << r.describe();
  EXPECT_NE(r.err.find("missing.gltf"), std::string::npos) << r.err;

  r = viewer({"--graph", "bad-graph.json"});
  EXPECT_EQ(r.exit_code, 1) << r.describe();
  EXPECT_NE(r.err.find("bad-graph.json"), std::string::npos) << r.err;

  r = viewer({"--graph", "graph.json", "--script", "bad-script.txt"});
  EXPECT_EQ(r.exit_code, 1) << r.describe();
  EXPECT_NE(r.err.find("bad-script.txt:2"), std::string::npos) << r.err;

  r = viewer({"--width", "zero"});
  EXPECT_EQ(r.exit_code, 2) << r.describe();

  // No display at all.
  ProcessOptions headless = options();
  headless.env["DISPLAY"] = std::nullopt;
  r = run_process(VOXGI_VIEWER_EXE, {"--graph", "graph.json"}, headless);
  EXPECT_EQ(r.exit_code, 1) << r.describe();
  EXPECT_NE(r.err.find("no display"), std::string::npos) << r.err;
  EXPECT_TRUE(r.exited()) << r.describe();
}

}  // namespace
}  // namespace voxgi::test
