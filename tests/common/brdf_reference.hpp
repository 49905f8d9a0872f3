#pragma once
// The glTF BRDF and KHR_lights_punctual falloffs evaluated on the CPU, written from the
// specifications independently of shaders/lib/brdf.glsl, as the expected value of GPU tests.

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

#include "engine/scene/scene.hpp"

namespace voxgi::test {

inline glm::vec3 gltf_brdf(const glm::vec3& base_color, float metallic, float roughness,
                           const glm::vec3& n, const glm::vec3& v, const glm::vec3& l) {
  const float pi = 3.14159265358979f;
  const float n_dot_l = glm::dot(n, l);
  const float n_dot_v = std::max(glm::dot(n, v), 1e-4f);
  if (n_dot_l <= 0.0f) return glm::vec3(0.0f);
  const glm::vec3 h = glm::normalize(l + v);
  const float n_dot_h = std::clamp(glm::dot(n, h), 0.0f, 1.0f);
  const float v_dot_h = std::clamp(glm::dot(v, h), 0.0f, 1.0f);
  const float alpha = roughness * roughness;
  const float a2 = alpha * alpha;

  const glm::vec3 f0 = glm::mix(glm::vec3(0.04f), base_color, metallic);
  const glm::vec3 c_diff = glm::mix(base_color, glm::vec3(0.0f), metallic);
  const glm::vec3 fresnel = f0 + (glm::vec3(1.0f) - f0) * std::pow(1.0f - v_dot_h, 5.0f);
  const float d_denominator = n_dot_h * n_dot_h * (a2 - 1.0f) + 1.0f;
  const float distribution = a2 / (pi * d_denominator * d_denominator);
  // Separable Smith: G1(x) = 2 n.x / (n.x + sqrt(a2 + (1 - a2)(n.x)^2)); V = G / (4 n.l n.v).
  const float g1_l = 2.0f * n_dot_l / (n_dot_l + std::sqrt(a2 + (1.0f - a2) * n_dot_l * n_dot_l));
  const float g1_v = 2.0f * n_dot_v / (n_dot_v + std::sqrt(a2 + (1.0f - a2) * n_dot_v * n_dot_v));
  const float visibility = g1_l * g1_v / (4.0f * n_dot_l * n_dot_v);
  return (glm::vec3(1.0f) - fresnel) * c_diff / pi + fresnel * distribution * visibility;
}

// Irradiance-normalised incident light at `p` (E along the light direction, before cos θ),
// and the unit direction towards the light.
inline glm::vec3 punctual_light_at(const scene::Light& light, const glm::vec3& p, glm::vec3& l) {
  const glm::vec3 radiance = light.color * light.intensity;
  if (light.type == scene::LightType::Directional) {
    l = -glm::normalize(light.direction);
    return radiance;
  }
  const glm::vec3 to_light = light.position - p;
  const float d2 = glm::dot(to_light, to_light);
  l = to_light / std::sqrt(d2);
  float attenuation = 1.0f / d2;
  if (light.range > 0.0f) {
    const float r = std::sqrt(d2) / light.range;
    attenuation *= std::clamp(1.0f - r * r * r * r, 0.0f, 1.0f);
  }
  if (light.type == scene::LightType::Spot) {
    const float cos_outer = std::cos(light.outer_cone);
    const float cos_inner = std::cos(light.inner_cone);
    const float scale = 1.0f / std::max(0.001f, cos_inner - cos_outer);
    const float offset = -cos_outer * scale;
    const float cd = glm::dot(glm::normalize(light.direction), -l);
    const float s = std::clamp(cd * scale + offset, 0.0f, 1.0f);
    attenuation *= s * s;
  }
  return radiance * attenuation;
}

}  // namespace voxgi::test
