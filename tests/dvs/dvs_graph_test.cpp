// graphs/dvs.json end to end (common.voxelize, dvs.voxel_lighting, vct.filter, dvs.voxel_bounce,
// vct.cone_trace, composite): a white furnace with the analytic radiance per bounce count,
// Cornell-box colour bleeding, identical static frames, and the hard cases that concern voxels,
// all without NaN or Inf. Volumes 32^3, images 48^2 or 64^2 to stay fast on lavapipe.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>

#include "dvs_runner.hpp"
#include "engine/scene/builtin_scenes.hpp"
#include "engine/scene/scene_builder.hpp"
#include "tests/common/hard_case_scenes.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

using scene::SceneBuilder;

DvsRunner::Setup graph_setup(scene::Scene scene, uint32_t size,
                             std::map<std::string, std::string> overrides = {}) {
  DvsRunner::Setup setup;
  setup.graph_path = "graphs/dvs.json";
  setup.scene = std::move(scene);
  setup.width = size;
  setup.height = size;
  overrides.emplace("voxel.resolution", "32");
  overrides.emplace("shadow.resolution", "256");
  setup.overrides = std::move(overrides);
  return setup;
}

size_t count_bad(const std::vector<float>& values) {
  size_t n = 0;
  for (float v : values) n += std::isfinite(v) && v >= 0.0f ? 0 : 1;
  return n;
}

double mean_channel(const std::vector<float>& rgba, int channel) {
  double sum = 0.0;
  for (size_t i = static_cast<size_t>(channel); i < rgba.size(); i += 4) sum += rgba[i];
  return sum / static_cast<double>(rgba.size() / 4);
}

// White furnace: a closed 2 m box, albedo 1, every wall emitting Le, no lights, the camera
// inside. With an ideal gather each bounce adds Le, so K voxel bounces give voxel radiance
// (K + 1) Le and the pixel Le (emission) + (K + 1) Le (the final gather): (K + 2) Le.
// The cone gather sees a share g < 1 of the walls (bounce tests), so the image falls short by
// an error that grows with K; this reports it and bounds it.
TEST_F(GpuTest, WhiteFurnaceMatchesTheRadiancePerBounce) {
  const float le = 0.5f;
  SceneBuilder b("furnace");
  const int white = b.add_material(matte(glm::vec3(1.0f), glm::vec3(le)));
  const float h = 1.0f;
  // Six inward-facing walls.
  b.add_quad("floor", {-h, -h, -h}, {0, 0, 2 * h}, {2 * h, 0, 0}, white);
  b.add_quad("ceiling", {-h, h, -h}, {2 * h, 0, 0}, {0, 0, 2 * h}, white);
  b.add_quad("back", {-h, -h, h}, {0, 2 * h, 0}, {2 * h, 0, 0}, white);
  b.add_quad("front", {-h, -h, -h}, {2 * h, 0, 0}, {0, 2 * h, 0}, white);
  b.add_quad("left", {-h, -h, -h}, {0, 2 * h, 0}, {0, 0, 2 * h}, white);
  b.add_quad("right", {h, -h, -h}, {0, 0, 2 * h}, {0, 2 * h, 0}, white);
  b.add_camera("inside", {0.0f, 0.0f, -0.5f}, {0.0f, 0.0f, 1.0f}, 1.2f);
  const scene::Scene furnace = b.finish();
  double previous = 0.0;
  for (int k = 0; k <= 3; ++k) {
    DvsRunner runner(graph_setup(furnace, 48, {{"dvs.bounces", std::to_string(k)}}));
    runner.render();
    const std::vector<float> linear = runner.read("linear");
    EXPECT_EQ(count_bad(linear), 0u);
    EXPECT_EQ(count_bad(runner.read("indirect")), 0u);
    const double mean = mean_channel(linear, 1);
    const double analytic = (k + 2) * le;
    const double error = (mean - analytic) / analytic;
    std::cout << "furnace K=" << k << ": mean " << mean << ", analytic " << analytic
              << ", relative error " << error << "\n";
    EXPECT_GT(mean, previous) << "a bounce added nothing";
    EXPECT_LE(mean, analytic * 1.02) << "energy created with " << k << " bounces";
    EXPECT_GT(mean, analytic * (k == 0 ? 0.85 : 0.6)) << "too much energy lost with " << k;
    previous = mean;
  }
}

glm::ivec2 project(const DvsRunner& runner, glm::vec3 p, uint32_t size) {
  const glm::mat4 vp =
      scene::projection_matrix(runner.camera(), 1.0f) * scene::view_matrix(runner.camera());
  const glm::vec4 clip = vp * glm::vec4(p, 1.0f);
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  const glm::vec2 uv = ndc * 0.5f + 0.5f;
  return glm::ivec2(uv * static_cast<float>(size));
}

glm::vec3 average_around(const std::vector<float>& rgba, glm::ivec2 pixel, uint32_t size) {
  glm::vec3 sum(0.0f);
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const glm::ivec2 q = glm::clamp(pixel + glm::ivec2(dx, dy), glm::ivec2(0),
                                      glm::ivec2(static_cast<int>(size) - 1));
      const size_t i = (static_cast<size_t>(q.y) * size + static_cast<size_t>(q.x)) * 4;
      sum += glm::vec3(rgba[i], rgba[i + 1], rgba[i + 2]);
    }
  }
  return sum / 9.0f;
}

// The Cornell box: the indirect light on the ceiling is redder next to the red wall and
// greener next to the green wall; no NaN/Inf; a static scene renders identical frames.
TEST_F(GpuTest, CornellBoxBleedsColourAndStaticFramesAreIdentical) {
  const uint32_t size = 64;
  DvsRunner runner(graph_setup(scene::make_builtin_scene("cornell"), size));
  runner.render();
  const std::vector<float> first = runner.read("linear");
  const std::vector<float> indirect = runner.read("indirect");
  EXPECT_EQ(count_bad(first), 0u);
  EXPECT_EQ(count_bad(indirect), 0u);
  // The ceiling (y = 0.5488) a few centimetres from each side wall, halfway back.
  const glm::ivec2 near_red = project(runner, {0.50f, 0.5488f, 0.30f}, size);
  const glm::ivec2 near_green = project(runner, {0.06f, 0.5488f, 0.30f}, size);
  const glm::vec3 red_side = average_around(indirect, near_red, size);
  const glm::vec3 green_side = average_around(indirect, near_green, size);
  std::cout << "ceiling indirect near the red wall " << red_side.r << " " << red_side.g << " "
            << red_side.b << " (pixel " << near_red.x << "," << near_red.y
            << "), near the green wall " << green_side.r << " " << green_side.g << " "
            << green_side.b << " (pixel " << near_green.x << "," << near_green.y << ")\n";
  ASSERT_GT(red_side.r + red_side.g, 0.0f) << "no indirect light on the ceiling";
  EXPECT_GT(red_side.r / red_side.g, green_side.r / green_side.g)
      << "the ceiling near the red wall is not redder";
  EXPECT_GT(green_side.g / green_side.r, red_side.g / red_side.r)
      << "the ceiling near the green wall is not greener";

  runner.render();
  EXPECT_EQ(runner.read("linear"), first) << "frame 2 of a static scene differs";
  EXPECT_FALSE(runner.ran("voxel_lighting"));
  EXPECT_FALSE(runner.ran("bounce1"));
  runner.render();
  EXPECT_EQ(runner.read("linear"), first) << "frame 3 of a static scene differs";
}

// Through graphs/dvs.json: when only the Cornell box's light moves, voxelization skips,
// dvs.voxel_lighting and the bounces run, and the image equals a fresh render with the light
// already moved.
TEST_F(GpuTest, MovingOnlyALightRelightsWithoutRevoxelization) {
  const uint32_t size = 48;
  const glm::vec3 moved(0.15f, 0.45f, 0.2f);
  DvsRunner runner(graph_setup(scene::make_builtin_scene("cornell"), size));
  runner.render();
  runner.render();
  EXPECT_FALSE(runner.ran("voxelize"));
  EXPECT_FALSE(runner.ran("voxel_lighting"));
  runner.move_light(0, moved);
  runner.render(/*lights_changed=*/true);
  EXPECT_FALSE(runner.ran("voxelize")) << "a light move revoxelized";
  EXPECT_TRUE(runner.ran("voxel_lighting")) << "a light move did not re-light the voxels";
  EXPECT_TRUE(runner.ran("bounce1"));
  for (const graph::Executor::PassTiming& t : runner.executor().timings()) {
    std::cout << "  " << t.pass << " " << (t.skipped.empty() ? "ran" : "skipped: " + t.skipped)
              << "\n";
  }
  const std::vector<float> relit = runner.read("linear");

  scene::Scene fresh_scene = scene::make_builtin_scene("cornell");
  fresh_scene.nodes.at(static_cast<size_t>(fresh_scene.lights.at(0).node)).translation = moved;
  DvsRunner fresh(graph_setup(fresh_scene, size));
  fresh.render();
  const std::vector<float> expected = fresh.read("linear");
  ASSERT_EQ(relit.size(), expected.size());
  double worst = 0.0;
  for (size_t i = 0; i < relit.size(); ++i) {
    worst = std::max(worst, static_cast<double>(std::abs(relit[i] - expected[i])));
  }
  std::cout << "re-lit vs fresh: largest difference " << worst << "\n";
  EXPECT_EQ(relit, expected) << "re-lit image differs from a fresh render";
}

struct HardCase {
  const char* name;
  std::function<scene::Scene()> make;
};

// The cases of HARD-CASES.md that reach the voxels of dvs.json.
std::vector<HardCase> hard_cases() {
  return {
      {"degenerate_triangles_and_zero_normals", [] { return degenerate_triangles(); }},
      {"thin_wall_normals_cancel", [] { return thin_wall(); }},
      {"light_on_a_surface_and_inside_geometry", light_on_a_surface_and_inside_geometry},
      {"very_bright_and_very_dim_emitters_only",
       [] {
         SceneBuilder b("emitters");
         const int bright = b.add_material(matte(glm::vec3(0.5f), glm::vec3(1e5f)));
         const int dim = b.add_material(matte(glm::vec3(0.5f), glm::vec3(1e-5f)));
         const int white = b.add_material(matte(glm::vec3(0.8f)));
         b.add_quad("bright", {-1, 0, -1}, {0, 0, 2}, {1, 0, 0}, bright);
         b.add_quad("dim", {0, 0, -1}, {0, 0, 2}, {1, 0, 0}, dim);
         b.add_box("box", {0.5f, 0.3f, 0.0f}, glm::vec3(0.3f), white);
         b.add_camera("top", {0, 3, 0.01f}, {0, 0, 0}, 0.8f);
         return b.finish();
       }},
      {"far_from_the_origin", [] { return lit_floor("far", glm::vec3(1e5f, 0, -1e5f), 1.0f); }},
      {"tiny_scene", [] { return lit_floor("tiny", glm::vec3(0.0f), 1e-3f); }},
      {"empty_scene", [] { return scene::make_builtin_scene("empty"); }},
      {"camera_inside_geometry",
       [] {
         SceneBuilder b("inside");
         const int white = b.add_material(matte(glm::vec3(0.8f)));
         b.add_box("room", {0, 0, 0}, glm::vec3(2.0f), white);
         b.add_box("block", {0, -0.5f, 0.5f}, glm::vec3(0.4f), white);
         b.add_light(point_light(5.0f), {0.5f, 0.5f, 0.5f});
         b.add_camera("inside", {0, -0.5f, 0.5f}, {0, 0, 1}, 1.0f);
         return b.finish();
       }},
      {"grazing_light", grazing_light},
      {"mirrored_node", mirrored_node},
  };
}

void PrintTo(const HardCase& c, std::ostream* os) {
  *os << c.name;
}

class DvsHardCasesTest : public GpuTest, public ::testing::WithParamInterface<HardCase> {};

TEST_P(DvsHardCasesTest, OutputsStayFiniteAndNonNegative) {
  DvsRunner runner(graph_setup(GetParam().make(), 48, {{"dvs.bounces", "2"}}));
  runner.render();
  runner.render();
  for (const char* output : {"linear", "display", "indirect"}) {
    EXPECT_EQ(count_bad(runner.read(output)), 0u) << GetParam().name << " " << output;
  }
}

INSTANTIATE_TEST_SUITE_P(Voxels, DvsHardCasesTest, ::testing::ValuesIn(hard_cases()),
                         [](const auto& param_info) { return std::string(param_info.param.name); });

}  // namespace
}  // namespace voxgi::test
