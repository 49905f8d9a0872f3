// dvs.voxel_lighting on voxels uploaded directly: a voxelized plane under a point, a spot and a
// directional light against albedo/pi * E * cos(theta) evaluated on the CPU at every voxel
// centre; soft voxel-ray shadows (an occluded voxel is dark, the penumbra is monotonic);
// re-lighting without revoxelization; lights on and inside voxels stay finite.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>

#include "dvs_runner.hpp"
#include "engine/scene/scene_builder.hpp"
#include "lighting_graph.hpp"
#include "tests/common/brdf_reference.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

constexpr uint32_t kRes = 32;
constexpr float kVoxel = 0.125f;  // a 4 m window
constexpr float kPi = 3.14159265358979f;
const glm::vec3 kAlbedo(0.8f, 0.6f, 0.4f);  // exact in rgba8

// One voxel layer of a floor at y in [0, kVoxel), facing +y, over the whole window.
VoxelValue floor_voxel(glm::vec3 c, float size) {
  VoxelValue v;
  if (c.y > 0.0f && c.y < size) {
    v.albedo = kAlbedo;
    v.opacity = 1.0f;
    v.normal = glm::vec3(0.0f, 1.0f, 0.0f);
  }
  return v;
}

scene::Scene scene_with_light(scene::LightType type, glm::vec3 position, glm::vec3 direction,
                              float intensity) {
  scene::SceneBuilder builder("dvs-light");
  scene::Light light;
  light.type = type;
  light.intensity = intensity;
  light.inner_cone = 0.3f;
  light.outer_cone = 0.6f;
  builder.add_light(light, position, direction);
  builder.add_camera("camera", glm::vec3(0.0f, 2.0f, 4.0f), glm::vec3(0.0f), 0.8f);
  return builder.finish();
}

std::shared_ptr<VoxelSourceData> floor_voxels(uint32_t levels = 1) {
  auto data = std::make_shared<VoxelSourceData>();
  data->grid = std::make_unique<VoxelGrid>(kRes, levels, kVoxel, glm::vec3(0.0f));
  data->grid->fill(floor_voxel);
  return data;
}

DvsRunner::Setup lighting_setup(scene::Scene scene, std::shared_ptr<VoxelSourceData> voxels,
                                const std::string& params, uint32_t levels = 1) {
  DvsRunner::Setup setup;
  setup.graph_text = voxel_lighting_graph(kRes, levels, params);
  setup.scene = std::move(scene);
  setup.voxels = std::move(voxels);
  return setup;
}

struct LightCase {
  const char* name;
  scene::LightType type;
  glm::vec3 position;
  glm::vec3 direction;
  float intensity;
  const char* occlusion;
};

void PrintTo(const LightCase& c, std::ostream* os) {
  *os << c.name;
}

class VoxelDirectLightingTest : public GpuTest, public ::testing::WithParamInterface<LightCase> {};

// The shader evaluates the same formula at the voxel centre in float and stores half floats;
// 0.5% covers the half rounding (2^-11) with margin.
TEST_P(VoxelDirectLightingTest, PlaneMatchesAnalyticRadianceWithinHalfPercent) {
  const LightCase& lc = GetParam();
  auto voxels = floor_voxels();
  DvsRunner runner(
      lighting_setup(scene_with_light(lc.type, lc.position, lc.direction, lc.intensity), voxels,
                     std::string("\"occlusion\": \"") + lc.occlusion + "\""));
  runner.render();
  const std::vector<float> radiance = runner.read("radiance");
  const VoxelGrid& grid = *voxels->grid;
  const scene::Light& light = runner.scene().lights[0];
  const glm::vec3 n(0.0f, 1.0f, 0.0f);
  double worst = 0.0;
  int lit = 0, occupied = 0;
  for (int z = 0; z < static_cast<int>(kRes); ++z) {
    for (int y = 0; y < static_cast<int>(kRes); ++y) {
      for (int x = 0; x < static_cast<int>(kRes); ++x) {
        const glm::ivec3 v(x, y, z);
        const glm::vec3 c = grid.center(0, v);
        const glm::vec4 got = texel_rgba(radiance, grid.texel_index(0, v));
        const VoxelValue want = floor_voxel(c, kVoxel);
        if (want.opacity == 0.0f) {
          ASSERT_EQ(got, glm::vec4(0.0f)) << "empty voxel " << x << "," << y << "," << z;
          continue;
        }
        ++occupied;
        EXPECT_EQ(got.a, 1.0f);
        glm::vec3 l(0.0f);
        const glm::vec3 e = punctual_light_at(light, c, l);  // sets l
        const glm::vec3 expected = kAlbedo / kPi * e * std::max(glm::dot(n, l), 0.0f);
        for (int ch = 0; ch < 3; ++ch) {
          const double error =
              std::abs(got[ch] - expected[ch]) / std::max<double>(expected[ch], 1e-3);
          worst = std::max(worst, error);
          EXPECT_LT(error, 0.005) << lc.name << " voxel (" << x << "," << y << "," << z
                                  << ") channel " << ch << ": got " << got[ch] << ", expected "
                                  << expected[ch];
        }
        if (expected.g > 1e-3f) ++lit;
      }
    }
  }
  EXPECT_EQ(occupied, static_cast<int>(kRes * kRes));
  EXPECT_GT(lit, 50) << "too few lit voxels";
  std::cout << lc.name << " (" << lc.occlusion << "): " << occupied << " voxels, " << lit
            << " lit, worst relative error " << worst << "\n";
}

INSTANTIATE_TEST_SUITE_P(
    Lights, VoxelDirectLightingTest,
    ::testing::Values(
        LightCase{"point", scene::LightType::Point, {0.3f, 1.2f, -0.2f}, {0, -1, 0}, 8.0f, "none"},
        LightCase{
            "spot", scene::LightType::Spot, {-0.2f, 1.5f, 0.1f}, {0.2f, -1, 0}, 20.0f, "none"},
        LightCase{"directional",
                  scene::LightType::Directional,
                  {0, 3, 0},
                  {0.3f, -1, 0.2f},
                  3.0f,
                  "none"},
        // A lone plane must not shadow itself along its own voxels.
        LightCase{"point_voxel_rays",
                  scene::LightType::Point,
                  {0.3f, 1.2f, -0.2f},
                  {0, -1, 0},
                  8.0f,
                  "voxel_rays"},
        LightCase{"directional_grazing_voxel_rays",
                  scene::LightType::Directional,
                  {0, 3, 0},
                  {1.0f, -0.25f, 0.0f},
                  3.0f,
                  "voxel_rays"}),
    [](const ::testing::TestParamInfo<LightCase>& param) { return std::string(param.param.name); });

// The seed's attenuation (§2.1) of a voxel with unit normal n towards l: the axis faces the
// normal's signs select, weighted by the squared components.
float seed_normal_weighted_cosine(glm::vec3 n, glm::vec3 l) {
  float d = 0.0f;
  for (int k = 0; k < 3; ++k) d += n[k] * n[k] * std::max(n[k] > 0.0f ? l[k] : -l[k], 0.0f);
  return d;
}

// A plane whose voxels hold a tilted normal, under a directional light that faces it and one
// that grazes it from behind. "plane" (the default) lights it with its own cosine, max(N.L, 0),
// dark from behind; "normal_weighted" with the seed's per-axis attenuation, which lights the
// plane turned away from the light too. Half-float rounding as above.
TEST_F(GpuTest, TiltedPlaneTakesItsOwnCosineOrTheSeedsAttenuation) {
  const glm::vec3 n = glm::normalize(glm::vec3(0.6f, 0.8f, 0.0f));
  auto voxels = std::make_shared<VoxelSourceData>();
  voxels->grid = std::make_unique<VoxelGrid>(kRes, 1, kVoxel, glm::vec3(0.0f));
  voxels->grid->fill([&](glm::vec3 c, float size) {
    VoxelValue v = floor_voxel(c, size);
    if (v.opacity > 0.0f) v.normal = n;
    return v;
  });
  struct Case {
    const char* light;
    glm::vec3 to_light;
  };
  const Case cases[] = {{"facing", glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f))},
                        {"grazing_from_behind", glm::normalize(glm::vec3(-0.9f, 0.45f, 0.1f))}};
  for (const char* mode : {"plane", "normal_weighted"}) {
    for (const Case& c : cases) {
      DvsRunner runner(lighting_setup(
          scene_with_light(scene::LightType::Directional, {0, 3, 0}, -c.to_light, 3.0f), voxels,
          std::string("\"occlusion\": \"none\", \"cosine\": \"") + mode + "\""));
      runner.render();
      const std::vector<float> radiance = runner.read("radiance");
      const float cosine = std::string(mode) == "plane"
                               ? std::max(glm::dot(n, c.to_light), 0.0f)
                               : seed_normal_weighted_cosine(n, c.to_light);
      const glm::vec3 expected = kAlbedo / kPi * 3.0f * cosine;
      // Every voxel of the plane: a directional light sees them all alike.
      const VoxelGrid& grid = *voxels->grid;
      int occupied = 0;
      float worst = 0.0f;
      for (int z = 0; z < static_cast<int>(kRes); ++z) {
        for (int y = 0; y < static_cast<int>(kRes); ++y) {
          for (int x = 0; x < static_cast<int>(kRes); ++x) {
            const glm::ivec3 v(x, y, z);
            if (floor_voxel(grid.center(0, v), kVoxel).opacity == 0.0f) continue;
            ++occupied;
            const glm::vec4 got = texel_rgba(radiance, grid.texel_index(0, v));
            for (int ch = 0; ch < 3; ++ch) {
              const float error = std::abs(got[ch] - expected[ch]);
              worst = std::max(worst, error);
              ASSERT_LE(error, 0.005f * expected[ch] + 1e-6f)
                  << mode << ", " << c.light << ", voxel (" << x << "," << y << "," << z
                  << ") channel " << ch << ": got " << got[ch] << ", expected " << expected[ch];
            }
          }
        }
      }
      EXPECT_EQ(occupied, static_cast<int>(kRes * kRes));
      std::cout << mode << ", light " << c.light << ": cosine " << cosine
                << ", radiance (g) expected " << expected.g << ", worst error " << worst << "\n";
    }
  }
}

// A floor under a one-voxel-thick square slab 4 voxels above it, lit by a tilted directional
// light: floor voxels in the slab's shadow are dark, voxels far from it fully lit, and the
// visibility rises monotonically across the penumbra.
TEST_F(GpuTest, VoxelRayShadowsAreDarkAndThePenumbraIsMonotonic) {
  auto voxels = std::make_shared<VoxelSourceData>();
  voxels->grid = std::make_unique<VoxelGrid>(kRes, 1, kVoxel, glm::vec3(0.0f));
  const float slab_y = 4.5f * kVoxel;  // centre of the voxel layer 4 above the floor layer
  voxels->grid->fill([&](glm::vec3 c, float size) {
    VoxelValue v = floor_voxel(c, size);
    if (std::abs(c.y - slab_y) < 0.5f * size && std::abs(c.x) < 0.5f && std::abs(c.z) < 0.5f) {
      v.albedo = glm::vec3(0.5f);
      v.opacity = 1.0f;
      v.normal = glm::vec3(0.0f);  // top and bottom faces cancel
    }
    return v;
  });
  const glm::vec3 direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.0f));
  auto run = [&](const char* occlusion) {
    DvsRunner runner(
        lighting_setup(scene_with_light(scene::LightType::Directional, {0, 3, 0}, direction, 2.0f),
                       voxels, std::string("\"occlusion\": \"") + occlusion + "\""));
    runner.render();
    return runner.read("radiance");
  };
  const std::vector<float> shadowed = run("voxel_rays");
  const std::vector<float> open = run("none");
  const VoxelGrid& grid = *voxels->grid;
  // The slab's shadow on the floor is displaced by 0.3 * (slab height) along +x.
  const float shift = 0.3f * (slab_y - 0.5f * kVoxel);
  auto visibility_at = [&](float x) {
    const glm::ivec3 v = grid.window_voxel_at(0, glm::vec3(x, 0.5f * kVoxel, 0.0f));
    const size_t i = grid.texel_index(0, v);
    return texel_rgba(shadowed, i).g / texel_rgba(open, i).g;
  };
  EXPECT_LT(visibility_at(shift), 0.05f) << "the voxel under the slab's centre is lit";
  EXPECT_GT(visibility_at(shift + 1.5f), 0.999f) << "a voxel far from the slab is shadowed";
  EXPECT_GT(visibility_at(shift - 1.5f), 0.999f) << "a voxel far from the slab is shadowed";
  float previous = visibility_at(shift);
  std::cout << "penumbra (+x):";
  for (float x = shift + kVoxel; x < shift + 1.5f; x += kVoxel) {
    const float vis = visibility_at(x);
    std::cout << " " << vis;
    EXPECT_GE(vis, previous - 1e-3f) << "visibility falls at x = " << x;
    previous = vis;
  }
  std::cout << "\npenumbra (-x):";
  previous = visibility_at(shift);
  for (float x = shift - kVoxel; x > shift - 1.5f; x -= kVoxel) {
    const float vis = visibility_at(x);
    std::cout << " " << vis;
    EXPECT_GE(vis, previous - 1e-3f) << "visibility falls at x = " << x;
    previous = vis;
  }
  std::cout << "\n";
}

// Only a light moves: the voxel source skips (no revoxelization), dvs.voxel_lighting runs and
// gives exactly what a fresh run with the light already there gives. Unchanged frames skip.
TEST_F(GpuTest, RelightsWithoutRevoxelizationWhenOnlyALightMoves) {
  auto voxels = floor_voxels();
  const glm::vec3 moved(-0.6f, 0.9f, 0.4f);
  DvsRunner runner(lighting_setup(
      scene_with_light(scene::LightType::Point, {0.3f, 1.2f, -0.2f}, {0, -1, 0}, 8.0f), voxels,
      "\"occlusion\": \"voxel_rays\""));
  runner.render();
  EXPECT_TRUE(runner.ran("voxels"));
  EXPECT_TRUE(runner.ran("voxel_lighting"));
  const std::vector<float> before = runner.read("radiance");
  runner.render();
  EXPECT_FALSE(runner.ran("voxels"));
  EXPECT_EQ(runner.skipped("voxel_lighting"), "voxels, lights and shadow maps unchanged");
  EXPECT_EQ(runner.read("radiance"), before) << "a skipped frame changed the volume";

  runner.move_light(0, moved);
  runner.render(/*lights_changed=*/true);
  EXPECT_FALSE(runner.ran("voxels")) << "a light move revoxelized";
  EXPECT_TRUE(runner.ran("voxel_lighting")) << "a light move did not re-light the voxels";
  const std::vector<float> relit = runner.read("radiance");
  EXPECT_NE(relit, before);

  DvsRunner fresh(lighting_setup(scene_with_light(scene::LightType::Point, moved, {0, -1, 0}, 8.0f),
                                 floor_voxels(), "\"occlusion\": \"voxel_rays\""));
  fresh.render();
  EXPECT_EQ(relit, fresh.read("radiance")) << "re-lit volume differs from a fresh run";

  // New voxels (a revoxelization) re-light too, without any light change.
  voxels->grid->set(0, voxels->grid->window_voxel_at(0, {0.0f, 0.3f, 0.0f}),
                    VoxelValue{kAlbedo, 1.0f, {0.0f, 1.0f, 0.0f}, {}});
  ++voxels->revision;
  runner.render();
  EXPECT_TRUE(runner.ran("voxels"));
  EXPECT_TRUE(runner.ran("voxel_lighting")) << "new voxels did not re-light";
}

// A point light exactly at a floor voxel's centre and one inside a solid block of voxels:
// every value stays finite and below the half maximum, and the voxel holding the first light
// is lit as if the light were half a voxel above it.
TEST_F(GpuTest, LightsOnAndInsideVoxelsStayFinite) {
  for (const char* occlusion : {"none", "voxel_rays"}) {
    auto voxels = std::make_shared<VoxelSourceData>();
    voxels->grid = std::make_unique<VoxelGrid>(kRes, 2, kVoxel, glm::vec3(0.0f));
    voxels->grid->fill([](glm::vec3 c, float size) {
      VoxelValue v = floor_voxel(c, size);
      if (glm::all(glm::lessThan(glm::abs(c - glm::vec3(1.0f, 0.5f, 1.0f)), glm::vec3(0.3f)))) {
        v = VoxelValue{glm::vec3(0.9f), 1.0f, glm::vec3(0.0f), glm::vec3(0.0f)};  // solid block
      }
      return v;
    });
    scene::SceneBuilder builder("dvs-lights-in-voxels");
    scene::Light on_surface;
    on_surface.intensity = 100.0f;
    const glm::ivec3 holder = voxels->grid->window_voxel_at(0, {-0.5f, 0.01f, -0.5f});
    builder.add_light(on_surface, voxels->grid->center(0, holder));
    scene::Light inside = on_surface;
    inside.intensity = 1e6f;
    inside.range = 0.6f;  // keeps it off the first light's voxel
    builder.add_light(inside, glm::vec3(1.0f, 0.5f, 1.0f));
    DvsRunner runner(lighting_setup(builder.finish(), voxels,
                                    std::string("\"occlusion\": \"") + occlusion + "\"", 2));
    runner.render();
    const std::vector<float> radiance = runner.read("radiance");
    size_t bad = 0;
    float largest = 0.0f;
    for (float value : radiance) {
      if (!std::isfinite(value) || value < 0.0f || value > 65504.0f) ++bad;
      if (std::isfinite(value)) largest = std::max(largest, value);
    }
    EXPECT_EQ(bad, 0u) << occlusion << ": NaN, Inf, negative or out-of-range values";
    EXPECT_GT(largest, 0.0f) << occlusion << ": nothing lit";
    // albedo/pi * I / (voxel/2)^2, the light straight above (the light at the centre).
    const float expected = 0.8f / kPi * 100.0f / (0.25f * kVoxel * kVoxel);
    const glm::vec4 got = texel_rgba(radiance, voxels->grid->texel_index(0, holder));
    EXPECT_NEAR(got.r, expected, 0.005f * expected) << occlusion;
    std::cout << occlusion << ": largest radiance " << largest << "\n";
  }
}

// Emission is added per voxel, also where no light reaches; a voxel without albedo emits only.
TEST_F(GpuTest, EmissionIsAddedPerVoxel) {
  auto voxels = floor_voxels();
  const glm::ivec3 glowing = voxels->grid->window_voxel_at(0, {0.5f, 0.05f, 0.5f});
  voxels->grid->set(0, glowing, VoxelValue{glm::vec3(0.0f), 1.0f, {0, 1, 0}, {2.0f, 1.0f, 0.5f}});
  DvsRunner runner(
      lighting_setup(scene_with_light(scene::LightType::Directional, {0, 3, 0}, {0, -1, 0}, 1.0f),
                     voxels, "\"occlusion\": \"voxel_rays\""));
  runner.render();
  const std::vector<float> radiance = runner.read("radiance");
  const glm::vec4 got = texel_rgba(radiance, voxels->grid->texel_index(0, glowing));
  EXPECT_NEAR(got.r, 2.0f, 2e-3f);
  EXPECT_NEAR(got.g, 1.0f, 1e-3f);
  EXPECT_NEAR(got.b, 0.5f, 1e-3f);
  EXPECT_EQ(got.a, 1.0f);
  const std::vector<float> direct = runner.read("direct");
  EXPECT_EQ(direct, radiance) << "the 'direct' copy differs from 'radiance'";
}

}  // namespace
}  // namespace voxgi::test

namespace voxgi::test {
namespace {

// occlusion = shadow_map: common.shadow_maps renders the real geometry (a floor and a square
// occluder 0.5 m above it); floor voxels under the occluder are dark, voxels away from it
// match the unoccluded value.
TEST_F(GpuTest, ShadowMapOcclusionDarkensVoxelsBehindTheOccluder) {
  scene::SceneBuilder builder("dvs-shadow-map");
  scene::Material white;
  white.base_color = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
  white.roughness = 1.0f;
  white.metallic = 0.0f;
  const int material = builder.add_material(white);
  builder.add_quad("floor", {-2, 0, -2}, {0, 0, 4}, {4, 0, 0}, material);
  builder.add_quad("occluder", {-0.4f, 0.5f, -0.4f}, {0, 0, 0.8f}, {0.8f, 0, 0}, material);
  scene::Light light;
  light.intensity = 8.0f;
  builder.add_light(light, {0.0f, 1.5f, 0.0f});
  builder.add_camera("camera", {0, 3, 0.01f}, {0, 0, 0}, 0.8f);
  const scene::Scene scene = builder.finish();
  auto run = [&](const char* occlusion) {
    DvsRunner::Setup setup;
    setup.graph_text =
        voxel_lighting_graph(kRes, 1, std::string("\"occlusion\": \"") + occlusion + "\"", true);
    setup.scene = scene;
    setup.voxels = floor_voxels();
    DvsRunner runner(std::move(setup));
    runner.render();
    return runner.read("radiance");
  };
  const std::vector<float> shadowed = run("shadow_map");
  const std::vector<float> open = run("none");
  const VoxelGrid grid(kRes, 1, kVoxel, glm::vec3(0.0f));
  auto visibility_at = [&](float x, float z) {
    const size_t i = grid.texel_index(0, grid.window_voxel_at(0, {x, 0.05f, z}));
    return texel_rgba(shadowed, i).g / texel_rgba(open, i).g;
  };
  EXPECT_LT(visibility_at(0.0f, 0.0f), 0.05f) << "the voxel under the occluder is lit";
  EXPECT_LT(visibility_at(0.3f, -0.3f), 0.05f) << "a voxel under the occluder is lit";
  EXPECT_GT(visibility_at(1.5f, 0.0f), 0.99f) << "a voxel away from the occluder is shadowed";
  EXPECT_GT(visibility_at(-1.2f, 1.2f), 0.99f) << "a voxel away from the occluder is shadowed";
}

}  // namespace
}  // namespace voxgi::test
