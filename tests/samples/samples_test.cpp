// The sample apps, built and run as a user would, with their outputs checked.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

#include "engine/image/image.hpp"
#include "tests/apps/child_process.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

namespace fs = std::filesystem;

ProcessResult run_sample(const char* exe, const std::vector<std::string>& args,
                         const fs::path& dir) {
  ProcessOptions options;
  options.working_dir = dir;
  options.timeout = std::chrono::milliseconds(120000);
  options.env["VOXGI_VALIDATION"] = "1";  // a validation message fails the sample
  ProcessResult result = run_process(exe, args, options);
  EXPECT_EQ(result.err.find("vulkan validation"), std::string::npos) << result.err;
  return result;
}

double mean_abs_difference(const image::ImageRGBA32F& a, const image::ImageRGBA32F& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  if (a.pixels.size() != b.pixels.size() || a.pixels.empty()) return 0.0;
  double sum = 0.0;
  for (size_t i = 0; i < a.pixels.size(); i += 4) {
    for (size_t c = 0; c < 3; ++c) sum += std::abs(a.pixels[i + c] - b.pixels[i + c]);
  }
  return sum / (static_cast<double>(a.pixels.size()) * 0.75);
}

double mean_rgb(const image::ImageRGBA32F& img) {
  double sum = 0.0;
  for (size_t i = 0; i < img.pixels.size(); i += 4)
    sum += img.pixels[i] + img.pixels[i + 1] + img.pixels[i + 2];
  return img.pixels.empty() ? 0.0 : sum / (static_cast<double>(img.pixels.size()) * 0.75);
}

void expect_finite_non_negative(const image::ImageRGBA32F& img, const std::string& what) {
  size_t bad = 0;
  for (float v : img.pixels) bad += !std::isfinite(v) || v < 0.0f;
  EXPECT_EQ(bad, 0u) << what;
}

nlohmann::json read_json(const fs::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

TEST(Samples, CustomPipelineRendersAGraphBuiltInCode) {
  const fs::path dir = make_temp_dir("voxgi-sample-custom");
  const ProcessResult r = run_sample(
      SAMPLE_CUSTOM_PIPELINE, {"--width", "64", "--height", "48", "--out", "out/custom"}, dir);
  ASSERT_EQ(r.exit_code, 0) << r.describe();
  const image::ImageRGBA32F png = image::read_png(dir / "out/custom.png");
  EXPECT_EQ(png.width, 64u);
  EXPECT_EQ(png.height, 48u);
  EXPECT_GT(mean_rgb(png), 0.05) << "the Cornell box should be lit";
  const image::ImageRGBA32F exr = image::read_exr(dir / "out/custom.exr");
  expect_finite_non_negative(exr, "custom.exr");
  EXPECT_NE(r.out.find("lighting (common.deferred_lighting)"), std::string::npos) << r.out;

  const ProcessResult bad = run_sample(SAMPLE_CUSTOM_PIPELINE, {"--scene", "nowhere"}, dir);
  EXPECT_EQ(bad.exit_code, 1) << bad.describe();
  EXPECT_NE(bad.err.find("nowhere"), std::string::npos) << bad.err;
}

TEST(Samples, DynamicSceneWritesMovingFramesAndTimings) {
  const fs::path dir = make_temp_dir("voxgi-sample-dynamic");
  const ProcessResult r =
      run_sample(SAMPLE_DYNAMIC_SCENE,
                 {"--graph", std::string(VOXGI_SOURCE_DIR) + "/graphs/default.json", "--frames",
                  "4", "--width", "64", "--height", "48", "--out", "frames"},
                 dir);
  ASSERT_EQ(r.exit_code, 0) << r.describe();
  std::vector<image::ImageRGBA32F> frames;
  for (int i = 0; i < 4; ++i) {
    const fs::path file = dir / "frames" / ("frame-00" + std::to_string(i) + ".png");
    ASSERT_TRUE(fs::exists(file)) << file;
    frames.push_back(image::read_png(file));
    EXPECT_GT(mean_rgb(frames.back()), 0.01) << file;
  }
  // The box and the light move: consecutive frames differ.
  for (int i = 1; i < 4; ++i) EXPECT_GT(mean_abs_difference(frames[i - 1], frames[i]), 1e-4) << i;

  const nlohmann::json timings = read_json(dir / "frames" / "timings.json");
  EXPECT_EQ(timings["frames"].get<int>(), 4);
  std::vector<std::string> passes;
  for (const auto& p : timings["passes"]) {
    passes.push_back(p["pass"].get<std::string>());
    EXPECT_GE(p["gpu_ms"].get<double>(), 0.0);
  }
  EXPECT_NE(std::find(passes.begin(), passes.end(), "gbuffer"), passes.end());
  // The light moves every frame, so the shadow maps are never skipped.
  for (const auto& p : timings["passes"]) {
    if (p["pass"] == "shadows") {
      EXPECT_EQ(p["skipped"].get<int>(), 0);
    }
  }
  EXPECT_NE(r.out.find("total"), std::string::npos) << r.out;

  const ProcessResult bad =
      run_sample(SAMPLE_DYNAMIC_SCENE, {"--graph", "missing-graph.json"}, dir);
  EXPECT_EQ(bad.exit_code, 1) << bad.describe();
  EXPECT_NE(bad.err.find("missing-graph.json"), std::string::npos) << bad.err;
}

TEST(Samples, AbCompareWritesBothImagesTheirDifferenceAndBothTimings) {
  const fs::path dir = make_temp_dir("voxgi-sample-ab");
  const std::string graph = std::string(VOXGI_SOURCE_DIR) + "/graphs/default.json";
  const ProcessResult r =
      run_sample(SAMPLE_AB_COMPARE,
                 {"--a", graph, "--b", graph, "--set-b", "ambient.radiance=0.5", "--frames", "2",
                  "--width", "48", "--height", "48", "--out", "ab"},
                 dir);
  ASSERT_EQ(r.exit_code, 0) << r.describe();
  for (const char* file : {"a.png", "a.exr", "b.png", "b.exr", "difference.png", "difference.exr",
                           "a-timings.json", "b-timings.json"}) {
    EXPECT_TRUE(fs::exists(dir / "ab" / file)) << file;
  }
  const image::ImageRGBA32F a = image::read_exr(dir / "ab/a.exr");
  const image::ImageRGBA32F b = image::read_exr(dir / "ab/b.exr");
  const image::ImageRGBA32F d = image::read_exr(dir / "ab/difference.exr");
  expect_finite_non_negative(d, "difference.exr");
  // The difference image is |A - B| (to half precision).
  EXPECT_NEAR(mean_rgb(d), mean_abs_difference(a, b), 2e-3);
  EXPECT_GT(mean_rgb(d), 0.01) << "more ambient light in B must show";
  EXPECT_GT(read_json(dir / "ab/b-timings.json")["passes"].size(), 3u);
  // Run as one graph, the passes before the ambient term are shared and the images unchanged.
  EXPECT_NE(r.out.find("shared passes run once: gbuffer shadows lighting"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("merged display vs separate: A max |d| 0, B max |d| 0"), std::string::npos)
      << r.out;
  EXPECT_TRUE(fs::exists(dir / "ab" / "merged-timings.json"));

  // Two variants of vct.json that differ only in the cone count share the voxel pipeline.
  const ProcessResult variants =
      run_sample(SAMPLE_AB_COMPARE,
                 {"--a", std::string(VOXGI_SOURCE_DIR) + "/graphs/vct.json", "--b",
                  std::string(VOXGI_SOURCE_DIR) + "/graphs/vct.json", "--variant-b", "cones16",
                  "--set-a", "voxel.resolution=32", "--set-b", "voxel.resolution=32", "--frames",
                  "2", "--width", "32", "--height", "32", "--out", "variants"},
                 dir);
  ASSERT_EQ(variants.exit_code, 0) << variants.describe();
  const size_t line = variants.out.find("shared passes run once:");
  ASSERT_NE(line, std::string::npos) << variants.out;
  const std::string shared = variants.out.substr(line, variants.out.find('\n', line) - line);
  for (const char* pass : {" voxelize", " inject", " filter", " gbuffer"}) {
    EXPECT_NE(shared.find(pass), std::string::npos) << shared;
  }
  EXPECT_EQ(shared.find("cone_trace"), std::string::npos) << shared;

  // The same graph twice renders the same image: the difference is zero.
  const ProcessResult same = run_sample(SAMPLE_AB_COMPARE,
                                        {"--a", graph, "--b", graph, "--frames", "1", "--width",
                                         "32", "--height", "32", "--out", "same"},
                                        dir);
  ASSERT_EQ(same.exit_code, 0) << same.describe();
  EXPECT_EQ(mean_rgb(image::read_exr(dir / "same/difference.exr")), 0.0);

  const ProcessResult bad = run_sample(SAMPLE_AB_COMPARE, {"--set-b", "ambient.nope=1"}, dir);
  EXPECT_EQ(bad.exit_code, 1) << bad.describe();
  EXPECT_NE(bad.err.find("ambient.nope"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace voxgi::test
