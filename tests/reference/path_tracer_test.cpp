// The reference path tracer against closed-form answers: the white furnace (a closed box that
// emits and reflects everywhere) and a Lambertian plane under a point light; plus the
// progressive accumulation's contract (deterministic, resets, variance estimate, hard cases).

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "engine/graph/executor.hpp"
#include "engine/scene/builtin_scenes.hpp"
#include "engine/scene/scene_builder.hpp"
#include "tests/common/brdf_reference.hpp"
#include "tests/common/plane_scene_probe.hpp"
#include "tests/common/render_harness.hpp"
#include "tests/gpu/gpu_test_env.hpp"
#include "tests/reference/image_statistics.hpp"

namespace voxgi::test {
namespace {

class PathTracerTest : public GpuTest {};

// A closed 2 m box around the camera, every face emitting `le` with base colour `albedo`.
scene::Scene furnace_scene(float albedo, const glm::vec3& le) {
  scene::SceneBuilder b("furnace");
  scene::Material m;
  m.name = "emitting_wall";
  m.base_color = glm::vec4(glm::vec3(albedo), 1.0f);
  m.metallic = 0.0f;
  m.roughness = 1.0f;
  m.emissive = le;
  const int material = b.add_material(m);
  b.add_box("room", glm::vec3(0.0f), glm::vec3(2.0f), material);
  b.add_camera("inside", glm::vec3(0.1f, 0.2f, 0.3f), glm::vec3(0.5f, 0.0f, -1.0f), 1.2f);
  return b.finish();
}

struct FurnaceCase {
  float albedo;
  int max_depth;
  int rr_start;
  float expected_factor;  // radiance / Le
};

TEST_F(PathTracerTest, WhiteFurnaceConvergesToTheClosedForm) {
  // Lambert override, so the albedo is exactly the base colour (the glTF BRDF's Fresnel term
  // makes it angle-dependent). Infinite bounces: L = Le / (1 - rho) (depth 64 truncates below
  // 1e-6); albedo 1 and depth D without roulette: L = (D + 1) Le exactly in expectation.
  const glm::vec3 le(1.0f, 0.5f, 0.25f);
  const FurnaceCase cases[] = {{0.5f, 64, 2, 2.0f}, {0.8f, 64, 3, 5.0f}, {1.0f, 4, 64, 5.0f}};
  for (const FurnaceCase& c : cases) {
    RenderSetup setup;
    setup.scene_data = furnace_scene(c.albedo, le);
    setup.graph = "graphs/reference.json";
    setup.width = setup.height = 32;
    setup.overrides = {{"path_tracer.lambert", "true"},
                       {"path_tracer.max_depth", std::to_string(c.max_depth)},
                       {"path_tracer.rr_start", std::to_string(c.rr_start)},
                       {"path_tracer.samples_per_frame", "16"}};
    RenderHarness harness(setup);
    const auto start = std::chrono::steady_clock::now();
    harness.render(4);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const RenderedImage linear = harness.output("linear");
    const RenderedImage variance = harness.output("variance");
    expect_finite_non_negative(linear, "furnace linear");
    ASSERT_EQ(variance.at(0, 0).w, 64.0f) << "4 frames of 16 samples accumulated";
    const RenderedImage indirect_variance = harness.output("indirect_variance");
    ASSERT_EQ(indirect_variance.at(0, 0).w, 64.0f);
    for (int ch = 0; ch < 3; ++ch) {
      const MeanEstimate mean = image_mean(linear, variance, ch);
      const double expected = c.expected_factor * le[ch];
      // 5 standard errors of the image mean (from the tracer's own variance estimate) plus
      // float accumulation error.
      const double tolerance = 5.0 * mean.standard_error + 1e-4 * expected;
      EXPECT_NEAR(mean.value, expected, tolerance)
          << "albedo " << c.albedo << " depth " << c.max_depth << " channel " << ch;
      if (ch == 0) {
        std::cout << "furnace albedo " << c.albedo << " depth " << c.max_depth << ": mean "
                  << mean.value << " expected " << expected << " (error "
                  << (mean.value - expected) / expected * 100.0 << " %, standard error "
                  << mean.standard_error / expected * 100.0 << " %), 64 spp 32x32 in " << seconds
                  << " s\n";
      }
      // The variance estimate must describe the actual pixel-to-pixel spread (every pixel
      // estimates the same value here).
      const double ratio = mean.pixel_spread_variance / mean.mean_variance_estimate;
      EXPECT_GT(ratio, 0.6) << "variance output underestimates the noise, channel " << ch;
      EXPECT_LT(ratio, 1.6) << "variance output overestimates the noise, channel " << ch;
      // The same of the indirect layer's variance (what the bench takes as the noise of a
      // reference's indirect light).
      const MeanEstimate indirect = image_mean(harness.output("indirect"), indirect_variance, ch);
      const double indirect_ratio =
          indirect.pixel_spread_variance / indirect.mean_variance_estimate;
      EXPECT_GT(indirect_ratio, 0.6)
          << "indirect_variance underestimates the noise, channel " << ch;
      EXPECT_LT(indirect_ratio, 1.6) << "indirect_variance overestimates the noise, channel " << ch;
    }
  }
}

TEST_F(PathTracerTest, LambertianPlaneUnderPointLightMatchesTheAnalyticValue) {
  // One reflection (direct light only) through pixel centres: deterministic, so every floor
  // pixel must equal rho/pi * I cos(theta) / d^2 to float precision.
  RenderSetup setup;
  setup.scene = "plane-point";
  setup.graph = "graphs/reference.json";
  setup.width = setup.height = 64;
  setup.overrides = {{"path_tracer.lambert", "true"},
                     {"path_tracer.max_depth", "1"},
                     {"path_tracer.pixel_jitter", "false"}};
  RenderHarness harness(setup);
  harness.render(1);
  const RenderedImage image = harness.output("linear");
  expect_finite_non_negative(image, "plane linear");
  const PlaneSceneProbe probe(harness.scene());
  const scene::Light& light = harness.scene().lights.at(0);
  const float rho = probe.floor_material().base_color.r;
  int compared = 0, shadowed = 0;
  double worst = 0.0;
  for (uint32_t y = 0; y < image.height; ++y) {
    for (uint32_t x = 0; x < image.width; ++x) {
      const auto p = probe.floor_point(harness.view_proj(), x, y, image.width, image.height);
      if (!p) continue;
      const glm::vec3 to_light = light.position - *p;
      const float d2 = glm::dot(to_light, to_light);
      const float cos_theta = std::max(0.0f, to_light.y / std::sqrt(d2));
      const double expected = rho / M_PI * light.intensity * cos_theta / d2;
      const double got = image.at(x, y).r;
      if (probe.occluded(light, *p, -0.02f)) {
        EXPECT_LT(got, 1e-6) << "shadowed pixel (" << x << ", " << y << ") is lit";
        ++shadowed;
        continue;
      }
      if (!probe.occluded(light, *p, 0.02f)) {
        const double error = std::abs(got - expected) / expected;
        worst = std::max(worst, error);
        EXPECT_LT(error, 1e-3) << "pixel (" << x << ", " << y << "): " << got << " vs " << expected;
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 1000);
  EXPECT_GT(shadowed, 10);
  std::cout << "plane-point: " << compared << " lit pixels, worst relative error " << worst << ", "
            << shadowed << " shadowed pixels black\n";
}

TEST_F(PathTracerTest, GltfBrdfOnThePlaneScenesMatchesTheCpuBrdf) {
  // Direct light with the full glTF BRDF under point, spot and directional lights.
  for (const char* scene_name : kPlaneScenes) {
    RenderSetup setup;
    setup.scene = scene_name;
    setup.graph = "graphs/reference.json";
    setup.width = setup.height = 48;
    setup.overrides = {{"path_tracer.max_depth", "1"}, {"path_tracer.pixel_jitter", "false"}};
    RenderHarness harness(setup);
    harness.render(1);
    const RenderedImage image = harness.output("direct");
    const PlaneSceneProbe probe(harness.scene());
    const scene::Light& light = harness.scene().lights.at(0);
    const scene::Material& m = probe.floor_material();
    const glm::vec3 eye(harness.camera().world[3]);
    int compared = 0;
    for (uint32_t y = 0; y < image.height; ++y) {
      for (uint32_t x = 0; x < image.width; ++x) {
        const auto p = probe.floor_point(harness.view_proj(), x, y, image.width, image.height);
        if (!p || probe.occluded(light, *p, 0.02f)) continue;  // shadowed or near its edge
        glm::vec3 l;
        const glm::vec3 e = punctual_light_at(light, *p, l);
        const glm::vec3 n(0.0f, 1.0f, 0.0f);
        const glm::vec3 expected = gltf_brdf(glm::vec3(m.base_color), m.metallic, m.roughness, n,
                                             glm::normalize(eye - *p), l) *
                                   e * std::max(l.y, 0.0f);
        const glm::vec4 got = image.at(x, y);
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(got[c], expected[c], 5e-3 * std::max(expected[c], 1e-3f))
              << scene_name << " pixel (" << x << ", " << y << ") channel " << c;
        }
        ++compared;
      }
    }
    EXPECT_GT(compared, 300) << scene_name;
  }
}

TEST_F(PathTracerTest, AccumulationIsDeterministicAndRestartsOnChange) {
  RenderSetup setup;
  setup.scene = "cornell";
  setup.graph = "graphs/reference.json";
  setup.width = setup.height = 32;
  setup.overrides = {{"path_tracer.samples_per_frame", "2"}};
  RenderHarness a(setup);
  RenderHarness b(setup);
  a.render(3);
  b.render(3);
  const RenderedImage ia = a.output("linear");
  const RenderedImage ib = b.output("linear");
  ASSERT_EQ(ia.rgba, ib.rgba) << "the same (pixel, sample) pairs must give the same image";
  EXPECT_EQ(a.output("variance").at(5, 5).w, 6.0f);
  // Outputs add up: linear = direct + indirect.
  const RenderedImage direct = a.output("direct");
  const RenderedImage indirect = a.output("indirect");
  for (size_t i = 0; i < ia.rgba.size(); i += 4) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(ia.rgba[i + c], direct.rgba[i + c] + indirect.rgba[i + c],
                  1e-5f * std::max(1.0f, ia.rgba[i + c]));
    }
  }
  // A live parameter change starts the sums over.
  a.executor().set_param("path_tracer.max_depth", "2");
  a.render(1);
  EXPECT_EQ(a.output("variance").at(5, 5).w, 2.0f);
  // max_samples stops accumulating.
  a.executor().set_param("path_tracer.max_samples", "3");
  a.render(4);
  EXPECT_EQ(a.output("variance").at(5, 5).w, 3.0f);
}

// The built-in Cornell box's indirect light (16 x 16, 8 samples per pixel, one bounce, the
// deferred layers) with `cut`, more path_tracer parameters that leave part of it out.
RenderedImage cornell_indirect(const std::map<std::string, std::string>& cut) {
  RenderSetup setup;
  setup.scene = "cornell";
  setup.graph = "graphs/reference.json";
  setup.width = setup.height = 16;
  setup.overrides = {{"path_tracer.samples_per_frame", "4"},
                     {"path_tracer.max_depth", "2"},
                     {"path_tracer.deferred_layers", "true"}};
  for (const auto& [key, value] : cut) setup.overrides["path_tracer." + key] = value;
  RenderHarness harness(setup);
  harness.render(2);
  return harness.output("indirect");
}

// path_tracer.first_bounce_distance on the built-in Cornell box, whose ceiling light is an
// emitter (light sampling at the visible surface and BSDF sampling after it are both cut): the
// same (pixel, sample) paths lose only terms, so every pixel's indirect light is at most the
// unlimited one's, and a distance beyond the box changes no bit. (AnalyticIndirectTest checks
// the cut against a closed form.)
TEST_F(PathTracerTest, FirstBounceDistanceOnlyLeavesLightOut) {
  const RenderedImage all = cornell_indirect({});
  const RenderedImage beyond = cornell_indirect({{"first_bounce_distance", "10"}});
  const RenderedImage near = cornell_indirect({{"first_bounce_distance", "0.2"}});
  EXPECT_EQ(beyond.rgba, all.rgba);
  double sum_all = 0.0, sum_near = 0.0;
  for (size_t i = 0; i < all.rgba.size(); i += 4) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_LE(near.rgba[i + c], all.rgba[i + c]) << "pixel " << i / 4;
      sum_all += all.rgba[i + c];
      sum_near += near.rgba[i + c];
    }
  }
  std::printf("Cornell box, indirect light of first reflections within 0.2: %.3f of all\n",
              sum_near / sum_all);
  EXPECT_GT(sum_near, 0.0);
  EXPECT_LT(sum_near, 0.95 * sum_all);
}

// Four bands of the first reflection's sin^2 (path_tracer.first_bounce_sin2_min / _max) split
// each path of the built-in Cornell box (an emitter: light sampling is banded by its own
// direction) into exactly one of them: their indirect light adds up to the whole, pixel by
// pixel, to float rounding.
TEST_F(PathTracerTest, FirstBounceBandsAddUpToTheWhole) {
  const RenderedImage whole = cornell_indirect({});
  std::vector<double> sum(whole.rgba.size(), 0.0);
  for (int band = 0; band < 4; ++band) {
    const RenderedImage part =
        cornell_indirect({{"first_bounce_sin2_min", std::to_string(0.25 * band)},
                          {"first_bounce_sin2_max", std::to_string(0.25 * (band + 1))}});
    for (size_t i = 0; i < sum.size(); ++i) sum[i] += part.rgba[i];
  }
  for (size_t i = 0; i < sum.size(); i += 4) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(sum[i + c], whole.rgba[i + c], 1e-5 * std::max(1.0f, whole.rgba[i + c]))
          << "pixel " << i / 4;
    }
  }
}

TEST_F(PathTracerTest, RefitAfterAnInstanceMovedMatchesARebuild) {
  // Render a frame, move the tall block, render again with geometry_changed (the pass refits
  // its BVH): the image equals that of a fresh render of the moved scene (a rebuilt BVH).
  RenderSetup setup;
  setup.scene = "cornell";
  setup.graph = "graphs/reference.json";
  setup.width = setup.height = 32;
  setup.overrides = {{"path_tracer.samples_per_frame", "4"}};
  RenderHarness moving(setup);
  moving.render(1);
  scene::Scene& scene = moving.scene();
  int block = -1;
  for (size_t i = 0; i < scene.nodes.size(); ++i) {
    if (scene.nodes[i].name == "tall_block") block = static_cast<int>(i);
  }
  ASSERT_GE(block, 0);
  scene.nodes[size_t(block)].translation += glm::vec3(-0.12f, 0.0f, -0.1f);
  scene.update_transforms();
  moving.render(1, runtime::FrameChanges{false, false, true});
  const RenderedImage refitted = moving.output("linear");
  ASSERT_EQ(moving.output("variance").at(0, 0).w, 4.0f) << "the sums restarted";

  setup.scene_data = scene;
  RenderHarness fresh(setup);
  fresh.render(1);
  const RenderedImage rebuilt = fresh.output("linear");
  // Both trace the same rays with the same random numbers; only float rounding of the two
  // trees' frames differs, which may send a rare path elsewhere.
  size_t differing = 0;
  for (size_t i = 0; i < rebuilt.rgba.size(); ++i) {
    if (std::abs(refitted.rgba[i] - rebuilt.rgba[i]) > 1e-3f * std::max(1.0f, rebuilt.rgba[i])) {
      ++differing;
    }
  }
  EXPECT_LT(differing, rebuilt.rgba.size() / 50) << "refitted and rebuilt BVH images differ";
}

TEST_F(PathTracerTest, HardCasesStayFiniteAndNonNegative) {
  // Empty scene, a light inside a surface, a scene 1e5 m from the origin, very bright and very
  // dim emitters: every output finite and non-negative.
  {
    RenderSetup setup;
    setup.scene = "empty";
    setup.graph = "graphs/reference.json";
    setup.width = setup.height = 16;
    RenderHarness harness(setup);
    harness.render(2);
    const RenderedImage linear = harness.output("linear");
    expect_finite_non_negative(linear, "empty linear");
    for (float v : linear.rgba) {
      if (v != 1.0f) {
        EXPECT_EQ(v, 0.0f);  // alpha 1, radiance 0
      }
    }
  }
  scene::SceneBuilder b("hard");
  scene::Material bright;
  bright.base_color = glm::vec4(0.7f);
  bright.metallic = 0.0f;
  bright.roughness = 0.2f;
  bright.emissive = glm::vec3(1e5f);
  scene::Material dim = bright;
  dim.emissive = glm::vec3(1e-5f);
  dim.roughness = 0.03f;
  dim.metallic = 1.0f;
  const int bright_m = b.add_material(bright);
  const int dim_m = b.add_material(dim);
  const glm::vec3 offset(1e5f, 0.0f, -1e5f);
  b.add_quad("floor", offset + glm::vec3(-1, 0, -1), {0, 0, 2}, {2, 0, 0}, dim_m);
  b.add_box("lamp", offset + glm::vec3(0.3f, 0.2f, 0.0f), glm::vec3(0.1f), bright_m);
  b.add_quad("degenerate", offset, {0, 0, 0}, {1, 0, 0}, bright_m);
  scene::Light on_surface;
  on_surface.type = scene::LightType::Point;
  on_surface.intensity = 50.0f;
  b.add_light(on_surface, offset);  // exactly on the floor
  b.add_camera("view", offset + glm::vec3(0.0f, 1.5f, 2.0f), offset, 1.0f);
  RenderSetup setup;
  setup.scene_data = b.finish();
  setup.graph = "graphs/reference.json";
  setup.width = setup.height = 24;
  setup.overrides = {{"path_tracer.samples_per_frame", "4"}};
  RenderHarness harness(setup);
  harness.render(2);
  for (const char* output : {"linear", "direct", "indirect", "variance", "indirect_variance"}) {
    expect_finite_non_negative(harness.output(output), std::string("hard case ") + output);
  }
  const RenderedImage linear = harness.output("linear");
  double sum = 0.0;
  for (size_t i = 0; i < linear.rgba.size(); i += 4) sum += linear.rgba[i];
  EXPECT_GT(sum, 0.0) << "the far-away scene must be visible";
}

}  // namespace
}  // namespace voxgi::test
