// The reference path tracer's sampling of the glTF BRDF against the BRDF's directional albedo:
// a floor of one glTF material inside a closed box whose other faces emit radiance 1 (and
// reflect nothing that is seen: paths end at the first emitter hit). The radiance leaving the
// floor towards the camera is then exactly the directional albedo
//   a(v) = ∫ f(v, l) (n·l) dω_l,
// which the CPU computes by deterministic quadrature of tests/common/brdf_reference.hpp. Any
// energy lost or gained by lobe selection, the GGX visible-normal pdf, the MIS weights of
// BSDF-sampled emitter hits against next-event estimation, or the (1 − F) diffuse weighting
// shows here, per material and view angle.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <string>

#include "engine/scene/scene_builder.hpp"
#include "tests/common/brdf_reference.hpp"
#include "tests/common/render_harness.hpp"
#include "tests/gpu/gpu_test_env.hpp"
#include "tests/reference/image_statistics.hpp"

namespace voxgi::test {
namespace {

class BrdfAlbedoTest : public GpuTest {};

constexpr float kPi = 3.14159265358979f;

// The diffuse term of the glTF BRDF, (1 − F(v·h)) c_diff / π; the specular term is
// gltf_brdf() minus this.
glm::vec3 diffuse_term(const glm::vec3& base_color, float metallic, const glm::vec3& v,
                       const glm::vec3& l) {
  const glm::vec3 f0 = glm::mix(glm::vec3(0.04f), base_color, metallic);
  const glm::vec3 c_diff = glm::mix(base_color, glm::vec3(0.0f), metallic);
  const float v_dot_h = std::clamp(glm::dot(v, glm::normalize(l + v)), 0.0f, 1.0f);
  const glm::vec3 fresnel = f0 + (glm::vec3(1.0f) - f0) * std::pow(1.0f - v_dot_h, 5.0f);
  return (glm::vec3(1.0f) - fresnel) * c_diff / kPi;
}

// Directional albedo of the glTF BRDF for the unit view direction v above n = +Y, its diffuse
// and specular terms each integrated by its own midpoint quadrature: the diffuse term over
// cosine-weighted directions, the specular term over half vectors distributed as D(h) (n·h),
// mapped to l = reflect(−v, h) with dω_l = 4 (v·h) dω_h.
glm::vec3 directional_albedo(const glm::vec3& base_color, float metallic, float roughness,
                             const glm::vec3& v, int steps = 512) {
  const glm::vec3 n(0.0f, 1.0f, 0.0f);
  const glm::vec3 t(1.0f, 0.0f, 0.0f);
  const glm::vec3 b(0.0f, 0.0f, 1.0f);
  const float alpha = roughness * roughness;
  const float a2 = alpha * alpha;
  glm::dvec3 sum(0.0);
  for (int i = 0; i < steps; ++i) {
    const float u1 = (static_cast<float>(i) + 0.5f) / static_cast<float>(steps);
    for (int j = 0; j < steps; ++j) {
      const float phi = 2.0f * kPi * (static_cast<float>(j) + 0.5f) / static_cast<float>(steps);
      // Diffuse: l with pdf (n·l)/π, so each sample contributes f_diffuse π.
      const float r = std::sqrt(u1);
      const glm::vec3 l_d = t * (r * std::cos(phi)) + b * (r * std::sin(phi)) +
                            n * std::sqrt(std::max(0.0f, 1.0f - u1));
      sum += glm::dvec3(diffuse_term(base_color, metallic, v, l_d) * kPi);
      // Specular: h with pdf D(h) (n·h), i.e. tan²θ_h = α² u / (1 − u).
      const float cos_h = 1.0f / std::sqrt(1.0f + a2 * u1 / (1.0f - u1));
      const float sin_h = std::sqrt(std::max(0.0f, 1.0f - cos_h * cos_h));
      const glm::vec3 h = t * (sin_h * std::cos(phi)) + b * (sin_h * std::sin(phi)) + n * cos_h;
      const float v_dot_h = glm::dot(v, h);
      if (v_dot_h <= 0.0f) continue;
      const glm::vec3 l = 2.0f * v_dot_h * h - v;
      const float n_dot_l = glm::dot(n, l);
      if (n_dot_l <= 0.0f) continue;
      const float d_denominator = cos_h * cos_h * (a2 - 1.0f) + 1.0f;
      const float distribution = a2 / (kPi * d_denominator * d_denominator);
      const float pdf_l = distribution * cos_h / (4.0f * v_dot_h);
      const glm::vec3 f_specular = gltf_brdf(base_color, metallic, roughness, n, v, l) -
                                   diffuse_term(base_color, metallic, v, l);
      sum += glm::dvec3(f_specular * (n_dot_l / pdf_l));
    }
  }
  return glm::vec3(sum / (static_cast<double>(steps) * steps));
}

// A 2 m box standing on the floor y = 0: the floor has `floor`, the five other faces emit
// radiance 1 and are black. The camera looks at the floor's centre from `view_angle` off the
// normal through a narrow field of view (±1.4°), so every pixel sees nearly one angle.
// With `textured`, the floor's base colour and metallic-roughness come from constant 4 × 4
// textures (kBaseColorTexel, sRGB; kMetallicRoughnessTexel, linear: roughness in green,
// metallic in blue) multiplying the material's factors.
constexpr uint8_t kBaseColorTexel[4] = {188, 160, 100, 255};
constexpr uint8_t kMetallicRoughnessTexel[4] = {0, 128, 153, 255};

scene::Texture constant_texture(const std::string& name, const uint8_t (&texel)[4], bool srgb) {
  scene::Texture texture;
  texture.name = name;
  texture.width = texture.height = 4;
  texture.srgb = srgb;
  for (int i = 0; i < 16; ++i) texture.pixels.insert(texture.pixels.end(), texel, texel + 4);
  return texture;
}

float srgb_to_linear(uint8_t value) {
  const float c = static_cast<float>(value) / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

scene::Scene albedo_scene(scene::Material floor, float view_angle, bool textured) {
  scene::SceneBuilder builder("albedo-box");
  if (textured) {
    floor.base_color_tex = builder.add_texture(constant_texture("base", kBaseColorTexel, true));
    floor.metallic_roughness_tex =
        builder.add_texture(constant_texture("mr", kMetallicRoughnessTexel, false));
  }
  scene::Material emitter;
  emitter.name = "emitter";
  emitter.base_color = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  emitter.metallic = 0.0f;
  emitter.roughness = 1.0f;
  emitter.emissive = glm::vec3(1.0f);
  emitter.double_sided = true;
  const int e = builder.add_material(emitter);
  const int f = builder.add_material(floor);
  builder.add_quad("floor", {-1.0f, 0.0f, -1.0f}, {0.0f, 0.0f, 2.0f}, {2.0f, 0.0f, 0.0f}, f);
  builder.add_quad("ceiling", {-1.0f, 2.0f, -1.0f}, {2.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 2.0f}, e);
  builder.add_quad("left", {-1.0f, 0.0f, -1.0f}, {0.0f, 2.0f, 0.0f}, {0.0f, 0.0f, 2.0f}, e);
  builder.add_quad("right", {1.0f, 0.0f, -1.0f}, {0.0f, 0.0f, 2.0f}, {0.0f, 2.0f, 0.0f}, e);
  builder.add_quad("back", {-1.0f, 0.0f, -1.0f}, {2.0f, 0.0f, 0.0f}, {0.0f, 2.0f, 0.0f}, e);
  builder.add_quad("front", {-1.0f, 0.0f, 1.0f}, {0.0f, 2.0f, 0.0f}, {2.0f, 0.0f, 0.0f}, e);
  const glm::vec3 eye = 0.9f * glm::vec3(std::sin(view_angle), std::cos(view_angle), 0.0f);
  builder.add_camera("view", eye, glm::vec3(0.0f), 0.05f);
  return builder.finish();
}

struct AlbedoCase {
  glm::vec3 base_color;
  float roughness;
  float metallic;
  float view_degrees;
  bool textured = false;  // base colour and roughness × metallic from textures
};

TEST_F(BrdfAlbedoTest, FloorInAnEmittingBoxReflectsItsDirectionalAlbedo) {
  const glm::vec3 white(0.725f, 0.71f, 0.68f);  // the Cornell box's walls
  const glm::vec3 gold(1.0f, 0.78f, 0.34f);
  const AlbedoCase cases[] = {
      {white, 1.0f, 0.0f, 0.0f},
      {white, 1.0f, 0.0f, 60.0f},
      {white, 1.0f, 0.0f, 82.0f},
      {glm::vec3(0.8f), 0.5f, 0.0f, 45.0f},
      {glm::vec3(0.8f), 0.3f, 0.0f, 75.0f},
      {gold, 0.4f, 1.0f, 30.0f},
      {gold, 1.0f, 1.0f, 70.0f},
      {glm::vec3(0.5f, 0.3f, 0.1f), 0.7f, 0.5f, 50.0f},
      // Factors × texels: base colour sRGB-decoded, roughness 0.9 × 128/255, metallic 153/255.
      {glm::vec3(1.0f), 0.9f, 1.0f, 40.0f, true},
  };
  for (const AlbedoCase& c : cases) {
    scene::Material floor;
    floor.name = "floor";
    floor.base_color = glm::vec4(c.base_color, 1.0f);
    floor.roughness = c.roughness;
    floor.metallic = c.metallic;
    const float angle = glm::radians(c.view_degrees);
    RenderSetup setup;
    setup.scene_data = albedo_scene(floor, angle, c.textured);
    setup.graph = "graphs/reference.json";
    setup.width = setup.height = 32;
    // Paths end at the first emitter hit: the floor's one reflection is all that is measured.
    setup.overrides = {{"path_tracer.max_depth", "1"},
                       {"path_tracer.rr_start", "64"},
                       {"path_tracer.samples_per_frame", "64"}};
    RenderHarness harness(setup);
    const auto start = std::chrono::steady_clock::now();
    harness.render(4);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const RenderedImage linear = harness.output("linear");
    const RenderedImage variance = harness.output("variance");
    expect_finite_non_negative(linear, "albedo box linear");
    const glm::vec3 v(std::sin(angle), std::cos(angle), 0.0f);
    glm::vec3 base_color = c.base_color;
    float roughness = c.roughness;
    float metallic = c.metallic;
    if (c.textured) {
      for (int ch = 0; ch < 3; ++ch) base_color[ch] *= srgb_to_linear(kBaseColorTexel[ch]);
      roughness *= static_cast<float>(kMetallicRoughnessTexel[1]) / 255.0f;
      metallic *= static_cast<float>(kMetallicRoughnessTexel[2]) / 255.0f;
    }
    const glm::vec3 expected = directional_albedo(base_color, metallic, roughness, v);
    for (int ch = 0; ch < 3; ++ch) {
      const MeanEstimate mean = image_mean(linear, variance, ch);
      // 5 standard errors of the image mean plus the quadrature's and the field of view's
      // error (both well under 0.3%).
      const double tolerance = 5.0 * mean.standard_error + 0.005 * expected[ch];
      EXPECT_NEAR(mean.value, expected[ch], tolerance)
          << "base colour channel " << base_color[ch] << ", roughness " << roughness
          << ", metallic " << metallic << (c.textured ? " (textures)" : "") << ", view "
          << c.view_degrees << "°, channel " << ch;
      if (ch == 0) {
        std::cout << "r " << roughness << " m " << metallic << " c " << base_color.r
                  << (c.textured ? " (textures)" : "") << " view " << c.view_degrees << "°: traced "
                  << mean.value << ", albedo " << expected[ch] << " (error "
                  << (mean.value / expected[ch] - 1.0) * 100.0 << " %, standard error "
                  << mean.standard_error / expected[ch] * 100.0 << " %), 256 spp 32x32 in "
                  << seconds << " s\n";
      }
    }
  }
}

}  // namespace
}  // namespace voxgi::test
