// The hard cases of HARD-CASES.md that concern voxels, through graphs/vct.json: every output
// (linear, indirect, ao) stays finite and non-negative, AO stays in [0, 1], and the
// validation layer stays silent (GpuTest). Cases: empty scene, no lights, emissive only,
// very bright and dim emitters, camera inside geometry and outside the voxel volume, cones
// leaving the volume, grazing light and view, thin double-sided walls (faces cancel in a
// voxel), degenerate triangles, far from the origin, tiny scene, glossy metal and a mirror
// (the specular pass, at half resolution), several clipmap levels.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>
#include <ostream>

#include "engine/scene/builtin_scenes.hpp"
#include "engine/scene/scene_builder.hpp"
#include "tests/common/hard_case_scenes.hpp"
#include "tests/common/render_harness.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

using scene::Light;
using scene::LightType;
using scene::Material;
using scene::SceneBuilder;

// The surfaces of these cases: matte() but with metallic left at the glTF default (1), as the
// cases were first written.
Material surface(glm::vec3 albedo, glm::vec3 emissive = glm::vec3(0.0f)) {
  Material m = matte(albedo, emissive);
  m.metallic = Material{}.metallic;
  return m;
}

scene::Scene lit_floor(const std::string& name, glm::vec3 offset, float scale, glm::vec3 eye) {
  return test::lit_floor(name, offset, scale, eye, "view", surface(glm::vec3(0.8f)));
}

struct HardCase {
  const char* name;
  std::function<scene::Scene()> make;
  int levels = 1;
  std::map<std::string, std::string> overrides = {};
};

// Test names and ctest show the case's name, not its bytes.
void PrintTo(const HardCase& c, std::ostream* os) {
  *os << c.name;
}

std::vector<HardCase> hard_cases() {
  return {
      {"empty_scene", [] { return scene::make_builtin_scene("empty"); }},
      {"no_lights",
       [] {
         SceneBuilder b("no_lights");
         const int white = b.add_material(surface(glm::vec3(0.8f)));
         b.add_quad("floor", {-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, white);
         b.add_box("box", {0, 0.2f, 0}, glm::vec3(0.4f), white);
         b.add_camera("top", {0, 2, 1}, {0, 0, 0}, 0.8f);
         return b.finish();
       }},
      {"emissive_only_very_bright_and_dim",
       [] {
         SceneBuilder b("emitters");
         const int bright = b.add_material(surface(glm::vec3(0.5f), glm::vec3(1e5f)));
         const int dim = b.add_material(surface(glm::vec3(0.5f), glm::vec3(1e-5f)));
         const int white = b.add_material(surface(glm::vec3(0.8f)));
         b.add_quad("bright", {-1, 0, -1}, {0, 0, 2}, {1, 0, 0}, bright);
         b.add_quad("dim", {0, 0, -1}, {0, 0, 2}, {1, 0, 0}, dim);
         b.add_box("box", {0.5f, 0.2f, 0}, glm::vec3(0.3f), white);
         b.add_camera("top", {0, 2, 1}, {0, 0, 0}, 0.8f);
         return b.finish();
       }},
      {"camera_inside_geometry",
       [] {
         SceneBuilder b("inside");
         const int white = b.add_material(surface(glm::vec3(0.8f)));
         b.add_box("room", {0, 0, 0}, glm::vec3(2.0f), white);
         b.add_box("block", {0, 0, 0}, glm::vec3(0.2f), white);  // the camera is in here
         b.add_light(point_light(5.0f), {0.5f, 0.5f, 0.5f});
         b.add_camera("inside", {0, 0, 0}, {0, 0, 1}, 1.0f);
         return b.finish();
       }},
      {"camera_outside_the_volume",
       [] { return lit_floor("outside", glm::vec3(0.0f), 1.0f, glm::vec3(0, 6, 8)); }},
      {"grazing_light_and_view",
       [] {
         SceneBuilder b("grazing");
         const int white = b.add_material(surface(glm::vec3(0.8f)));
         b.add_quad("floor", {-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, white);
         b.add_box("box", {0.5f, 0.1f, 0}, glm::vec3(0.2f), white);
         Light sun;
         sun.type = LightType::Directional;
         sun.intensity = 3.0f;
         b.add_light(sun, {0, 1, 0}, glm::normalize(glm::vec3(1.0f, -1e-4f, 0.0f)));
         b.add_camera("grazing", {-2, 1e-3f, 0}, {2, 0, 0}, 0.8f);
         return b.finish();
       }},
      {"thin_double_sided_wall_and_light_on_it",
       [] {
         SceneBuilder b("thin");
         Material m = surface(glm::vec3(0.8f));
         m.double_sided = true;
         const int white = b.add_material(m);
         b.add_quad("floor", {-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, white);
         // Two faces with opposite normals 1 mm apart: their normals cancel in a voxel.
         b.add_quad("wall_a", {0, 0, -1}, {0, 1, 0}, {0, 0, 2}, white);
         b.add_quad("wall_b", {0.001f, 0, -1}, {0, 0, 2}, {0, 1, 0}, white);
         b.add_light(point_light(5.0f), {-0.0005f, 0.5f, 0.0f});  // on the wall
         b.add_camera("top", {0.5f, 2, 1.5f}, {0, 0.3f, 0}, 0.8f);
         return b.finish();
       }},
      {"degenerate_triangles", [] { return degenerate_triangles(surface(glm::vec3(0.8f))); }},
      {"far_from_the_origin",
       [] { return lit_floor("far", glm::vec3(1e5f, 0, -1e5f), 1.0f, glm::vec3(0, 2, 1.5f)); }},
      {"tiny_scene",
       [] { return lit_floor("tiny", glm::vec3(0.0f), 1e-3f, glm::vec3(0, 2, 1.5f)); }},
      {"glossy_metal_and_mirror_half_resolution",
       [] {
         SceneBuilder b("glossy");
         Material metal = surface(glm::vec3(0.9f, 0.6f, 0.3f));
         metal.metallic = 1.0f;
         metal.roughness = 0.3f;
         Material mirror = surface(glm::vec3(0.95f));
         mirror.metallic = 1.0f;
         mirror.roughness = 0.0f;
         const int floor = b.add_material(metal);
         const int wall = b.add_material(mirror);
         const int white = b.add_material(surface(glm::vec3(0.8f)));
         b.add_quad("floor", {-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, floor);
         b.add_quad("mirror", {-1, 0, -1}, {2, 0, 0}, {0, 1, 0}, wall);
         b.add_box("box", {0.3f, 0.2f, 0}, glm::vec3(0.4f), white);
         b.add_light(point_light(5.0f), {0, 1, 0.5f});
         b.add_camera("view", {0, 0.8f, 1.8f}, {0, 0.2f, 0}, 0.8f);
         return b.finish();
       },
       1,
       {{"cone_trace.resolution", "half"}, {"cone_trace_specular.resolution", "half"}}},
      {"three_clipmap_levels_camera_at_the_edge",
       [] { return lit_floor("levels", glm::vec3(0.0f), 1.0f, glm::vec3(0.9f, 0.3f, 0.9f)); }, 3},
  };
}

class VctHardCasesTest : public GpuTest, public ::testing::WithParamInterface<HardCase> {};

TEST_P(VctHardCasesTest, OutputsStayFiniteAndNonNegative) {
  RenderSetup setup;
  setup.scene_data = GetParam().make();
  setup.graph = "graphs/vct.json";
  setup.width = setup.height = 64;
  setup.overrides = GetParam().overrides;
  setup.overrides["voxel.levels"] = std::to_string(GetParam().levels);
  setup.overrides.emplace("voxel.resolution", "64");  // small volumes keep the suite fast
  RenderHarness harness(setup);
  harness.render(2);
  for (const char* output : {"linear", "indirect", "ao"}) {
    const RenderedImage image = harness.output(output);
    expect_finite_non_negative(image, std::string(GetParam().name) + " " + output);
    if (std::string(output) == "ao") {
      for (size_t i = 0; i < image.rgba.size(); i += 4) {
        ASSERT_LE(image.rgba[i], 1.0f) << "AO above 1";
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, VctHardCasesTest, ::testing::ValuesIn(hard_cases()),
                         [](const auto& c) { return std::string(c.param.name); });

}  // namespace
}  // namespace voxgi::test
