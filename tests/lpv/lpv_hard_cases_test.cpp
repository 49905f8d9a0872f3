// The hard cases of HARD-CASES.md that concern light propagation volumes, through
// graphs/lpv.json: every output (linear, indirect) stays finite and non-negative and the
// validation layer stays silent (GpuTest). Cases: empty scene, emitters only (very bright and
// very dim), a light on a surface and one inside geometry, a thin double-sided wall, degenerate
// triangles, the camera inside geometry and outside the volume, grazing light, a mirrored node,
// far from the origin, a tiny scene, spot and directional lights, three cascades with the
// camera at an edge, and seed 002's propagation factor 3 (and 16) over many iterations; the
// octree LPV on an empty scene, emitters only, a light inside geometry (index merge), three
// cascades and factor 16.

#include <gtest/gtest.h>

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
using scene::SceneBuilder;

struct HardCase {
  const char* name;
  std::function<scene::Scene()> make;
  std::map<std::string, std::string> overrides = {};
};

void PrintTo(const HardCase& c, std::ostream* os) {
  *os << c.name;
}

scene::Scene floor_lit_by(Light light, glm::vec3 position, glm::vec3 direction) {
  SceneBuilder b("lights");
  const int white = b.add_material(matte(glm::vec3(0.8f)));
  b.add_quad("floor", {-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, white);
  b.add_box("box", {0.3f, 0.2f, 0}, glm::vec3(0.4f), white);
  b.add_light(light, position, direction);
  b.add_camera("view", {0, 1.2f, 1.8f}, {0, 0.2f, 0}, 0.8f);
  return b.finish();
}

const std::map<std::string, std::string> kOctree = {{"lpv.octree_levels", "5"},
                                                    {"lpv.iterations", "4"}};

std::vector<HardCase> hard_cases() {
  return {
      {"empty_scene", [] { return scene::make_builtin_scene("empty"); }},
      {"emitters_only_very_bright_and_dim", [] { return very_bright_and_very_dim_emitters(); }},
      {"light_on_a_surface_and_inside_geometry",
       [] { return light_on_a_surface_and_inside_geometry(); }},
      {"thin_double_sided_wall", [] { return thin_wall(); }},
      {"degenerate_triangles", [] { return degenerate_triangles(); }},
      {"camera_inside_geometry", [] { return camera_inside_geometry(); }},
      {"camera_outside_the_volume",
       [] { return lit_floor("outside", glm::vec3(0.0f), 1.0f, glm::vec3(0, 6, 8)); }},
      {"grazing_light", [] { return grazing_light(); }},
      {"mirrored_node", [] { return mirrored_node(); }},
      {"far_from_the_origin",
       [] { return lit_floor("far", glm::vec3(1e5f, 0, -1e5f), 1.0f, glm::vec3(0, 2, 1.5f)); }},
      {"tiny_scene",
       [] { return lit_floor("tiny", glm::vec3(0.0f), 1e-3f, glm::vec3(0, 2, 1.5f)); }},
      {"spot_light",
       [] {
         Light spot;
         spot.type = LightType::Spot;
         spot.intensity = 20.0f;
         spot.outer_cone = 0.5f;
         return floor_lit_by(spot, {0, 1.5f, 0}, {0, -1, 0});
       }},
      {"directional_light",
       [] {
         Light sun;
         sun.type = LightType::Directional;
         sun.intensity = 3.0f;
         return floor_lit_by(sun, {0, 2, 0}, glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f)));
       }},
      {"three_cascades_camera_at_the_edge",
       [] { return lit_floor("levels", glm::vec3(0.0f), 1.0f, glm::vec3(0.9f, 0.3f, 0.9f)); },
       {{"voxel.levels", "3"}}},
      {"seed_factor_3_many_iterations",
       [] { return scene::make_builtin_scene("cornell"); },
       {{"propagate.factor", "3"}, {"lpv.iterations", "200"}}},
      {"factor_16_many_iterations",
       [] { return scene::make_builtin_scene("cornell"); },
       {{"propagate.factor", "16"}, {"lpv.iterations", "256"}}},
      // The octree LPV (five levels) on the cases that stress its levels and merges.
      {"octree_empty_scene", [] { return scene::make_builtin_scene("empty"); }, kOctree},
      {"octree_emitters_only", [] { return very_bright_and_very_dim_emitters(); }, kOctree},
      {"octree_index_light_inside_geometry",
       [] { return light_on_a_surface_and_inside_geometry(); },
       {{"lpv.octree_levels", "5"},
        {"lpv.iterations", "4"},
        {"propagate.merge", "index"},
        {"merge.merge", "index"}}},
      {"octree_three_cascades",
       [] { return lit_floor("levels", glm::vec3(0.0f), 1.0f, glm::vec3(0.9f, 0.3f, 0.9f)); },
       {{"voxel.levels", "3"}, {"lpv.octree_levels", "5"}, {"lpv.iterations", "4"}}},
      {"octree_factor_16_many_iterations",
       [] { return scene::make_builtin_scene("cornell"); },
       {{"lpv.octree_levels", "5"}, {"propagate.factor", "16"}, {"lpv.iterations", "256"}}},
  };
}

class LpvHardCasesTest : public GpuTest, public ::testing::WithParamInterface<HardCase> {};

TEST_P(LpvHardCasesTest, OutputsStayFiniteAndNonNegative) {
  RenderSetup setup;
  setup.scene_data = GetParam().make();
  setup.graph = "graphs/lpv.json";
  setup.width = setup.height = 48;
  setup.overrides = GetParam().overrides;
  setup.overrides.emplace("voxel.resolution", "32");
  setup.overrides.emplace("lpv.rsm_resolution", "64");
  RenderHarness harness(setup);
  harness.render(2);
  for (const char* output : {"linear", "indirect"}) {
    expect_finite_non_negative(harness.output(output), std::string(GetParam().name) + " " + output);
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, LpvHardCasesTest, ::testing::ValuesIn(hard_cases()),
                         [](const auto& c) { return std::string(c.param.name); });

}  // namespace
}  // namespace voxgi::test
