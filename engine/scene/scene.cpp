#include "engine/scene/scene.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtx/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace voxgi::scene {

glm::mat4 Node::local() const {
  if (matrix) return *matrix;
  return glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(rotation) *
         glm::scale(glm::mat4(1.0f), scale);
}

void TextureMapping::matrix_rows(glm::vec3& row0, glm::vec3& row1) const {
  // KHR_texture_transform: translation * rotation * scale, with its rotation matrix
  // (cos, sin; -sin, cos).
  const float c = std::cos(rotation), s = std::sin(rotation);
  row0 = glm::vec3(c * scale.x, s * scale.y, offset.x);
  row1 = glm::vec3(-s * scale.x, c * scale.y, offset.y);
}

glm::vec2 TextureMapping::apply(glm::vec2 uv) const {
  glm::vec3 row0, row1;
  matrix_rows(row0, row1);
  const glm::vec3 p(uv, 1.0f);
  return {glm::dot(row0, p), glm::dot(row1, p)};
}

void Scene::update_transforms() {
  // Iterative from the roots so deep hierarchies cannot overflow the stack; the loader has
  // already rejected cycles.
  std::vector<int> stack;
  for (size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].parent < 0) stack.push_back(static_cast<int>(i));
  }
  while (!stack.empty()) {
    const int index = stack.back();
    stack.pop_back();
    Node& node = nodes[static_cast<size_t>(index)];
    const glm::mat4 parent_world =
        node.parent >= 0 ? nodes[static_cast<size_t>(node.parent)].world : glm::mat4(1.0f);
    node.world = parent_world * node.local();
    for (int child : node.children) stack.push_back(child);
  }
  for (Light& light : lights) {
    if (light.node < 0 || light.node >= static_cast<int>(nodes.size())) continue;
    const glm::mat4& world = nodes[static_cast<size_t>(light.node)].world;
    light.position = glm::vec3(world[3]);
    const glm::vec3 dir = glm::mat3(world) * glm::vec3(0.0f, 0.0f, -1.0f);
    const float len = glm::length(dir);
    // A zero scale would make the direction degenerate; keep the previous one then.
    if (len > 1e-20f && std::isfinite(len)) light.direction = dir / len;
  }
  for (Camera& camera : cameras) {
    if (camera.node < 0 || camera.node >= static_cast<int>(nodes.size())) continue;
    camera.world = nodes[static_cast<size_t>(camera.node)].world;
  }
}

namespace {

// Index k of the key interval [times[k], times[k+1]) holding t, and the fraction within it.
void find_key(const std::vector<float>& times, float t, size_t& k, float& fraction) {
  if (times.size() < 2 || t <= times.front()) {
    k = 0;
    fraction = 0.0f;
    return;
  }
  if (t >= times.back()) {
    k = times.size() - 1;
    fraction = 0.0f;
    return;
  }
  const auto it = std::upper_bound(times.begin(), times.end(), t);
  k = static_cast<size_t>(it - times.begin()) - 1;
  const float span = times[k + 1] - times[k];
  fraction = span > 0.0f ? (t - times[k]) / span : 0.0f;
}

glm::vec4 sample_channel(const AnimationChannel& channel, float t) {
  size_t k = 0;
  float f = 0.0f;
  find_key(channel.times, t, k, f);
  const bool cubic = channel.interpolation == Interpolation::CubicSpline;
  auto value = [&](size_t key) { return channel.values[cubic ? key * 3 + 1 : key]; };
  const bool last = k + 1 >= channel.times.size();
  if (last || channel.interpolation == Interpolation::Step) return value(k);
  const bool rotation = channel.path == AnimationPath::Rotation;
  if (channel.interpolation == Interpolation::Linear) {
    if (!rotation) return glm::mix(value(k), value(k + 1), f);
    const glm::vec4 a = value(k), b = value(k + 1);
    const glm::quat q = glm::slerp(glm::quat(a.w, a.x, a.y, a.z), glm::quat(b.w, b.x, b.y, b.z), f);
    return glm::vec4(q.x, q.y, q.z, q.w);
  }
  // Cubic Hermite spline as the glTF spec defines it; tangents are scaled by the key span.
  const float dt = channel.times[k + 1] - channel.times[k];
  const float f2 = f * f, f3 = f2 * f;
  const glm::vec4 p0 = value(k), p1 = value(k + 1);
  const glm::vec4 m0 = channel.values[k * 3 + 2] * dt;
  const glm::vec4 m1 = channel.values[(k + 1) * 3] * dt;
  glm::vec4 result = (2 * f3 - 3 * f2 + 1) * p0 + (f3 - 2 * f2 + f) * m0 + (-2 * f3 + 3 * f2) * p1 +
                     (f3 - f2) * m1;
  if (rotation) {
    const float len = glm::length(result);
    result = len > 1e-20f ? result / len : glm::vec4(0, 0, 0, 1);
  }
  return result;
}

}  // namespace

bool Scene::animate(double time_seconds) {
  bool changed = false;
  for (const Animation& animation : animations) {
    float t = 0.0f;
    if (animation.duration > 0.0f && std::isfinite(time_seconds)) {
      t = static_cast<float>(std::fmod(time_seconds, static_cast<double>(animation.duration)));
      if (t < 0.0f) t += animation.duration;
    }
    for (const AnimationChannel& channel : animation.channels) {
      if (channel.node < 0 || channel.node >= static_cast<int>(nodes.size()) ||
          channel.times.empty()) {
        continue;
      }
      Node& node = nodes[static_cast<size_t>(channel.node)];
      const glm::vec4 v = sample_channel(channel, t);
      switch (channel.path) {
        case AnimationPath::Translation: {
          const glm::vec3 value(v);
          changed |= value != node.translation;
          node.translation = value;
          break;
        }
        case AnimationPath::Rotation: {
          const glm::quat value(v.w, v.x, v.y, v.z);
          changed |= value != node.rotation;
          node.rotation = value;
          break;
        }
        case AnimationPath::Scale: {
          const glm::vec3 value(v);
          changed |= value != node.scale;
          node.scale = value;
          break;
        }
      }
    }
  }
  if (changed) update_transforms();
  return changed;
}

std::vector<Instance> Scene::instances() const {
  std::vector<Instance> result;
  for (size_t n = 0; n < nodes.size(); ++n) {
    const Node& node = nodes[n];
    if (node.mesh < 0 || node.mesh >= static_cast<int>(meshes.size())) continue;
    const bool mirrored = glm::determinant(glm::mat3(node.world)) < 0.0f;
    const Mesh& mesh = meshes[static_cast<size_t>(node.mesh)];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      result.push_back(
          Instance{node.mesh, static_cast<int>(p), static_cast<int>(n), node.world, mirrored});
    }
  }
  return result;
}

void Scene::bounds(glm::vec3& mn, glm::vec3& mx) const {
  mn = glm::vec3(std::numeric_limits<float>::max());
  mx = glm::vec3(std::numeric_limits<float>::lowest());
  bool any = false;
  for (const Instance& instance : instances()) {
    const Primitive& primitive = meshes[static_cast<size_t>(instance.mesh)]
                                     .primitives[static_cast<size_t>(instance.primitive)];
    for (const Vertex& vertex : primitive.vertices) {
      const glm::vec3 p = glm::vec3(instance.world * glm::vec4(vertex.position, 1.0f));
      mn = glm::min(mn, p);
      mx = glm::max(mx, p);
      any = true;
    }
  }
  if (!any) mn = mx = glm::vec3(0.0f);
}

BoundingSphere Scene::bounding_sphere() const {
  glm::vec3 mn, mx;
  bounds(mn, mx);
  return {0.5f * (mn + mx), std::max(0.5f * glm::length(mx - mn), 1e-3f)};
}

SceneFeatures Scene::features() const {
  SceneFeatures f;
  const std::vector<Instance> all = instances();
  f.instance_count = static_cast<uint32_t>(all.size());
  std::vector<bool> used(materials.size(), false);
  for (const Instance& instance : all) {
    const Primitive& primitive = meshes[static_cast<size_t>(instance.mesh)]
                                     .primitives[static_cast<size_t>(instance.primitive)];
    f.triangle_count += static_cast<uint32_t>(primitive.indices.size() / 3);
    if (primitive.material >= 0 && primitive.material < static_cast<int>(materials.size())) {
      used[static_cast<size_t>(primitive.material)] = true;
    }
  }
  for (size_t m = 0; m < materials.size(); ++m) {
    if (!used[m]) continue;
    const Material& material = materials[m];
    if (glm::max(material.emissive.x, glm::max(material.emissive.y, material.emissive.z)) > 0.0f) {
      f.has_emissive = true;
    }
    if (material.roughness < 0.6f || material.metallic > 0.1f) f.has_glossy = true;
    for (int tex : {material.base_color_tex, material.metallic_roughness_tex, material.normal_tex,
                    material.occlusion_tex, material.emissive_tex}) {
      if (tex >= 0) f.has_textures = true;
    }
  }
  for (const Light& light : lights) {
    f.has_point_lights |= light.type == LightType::Point;
    f.has_spot_lights |= light.type == LightType::Spot;
    f.has_directional_lights |= light.type == LightType::Directional;
  }
  f.light_count = static_cast<uint32_t>(lights.size());
  for (const Animation& animation : animations) {
    for (const AnimationChannel& channel : animation.channels) {
      if (channel.node < 0 || channel.node >= static_cast<int>(nodes.size())) continue;
      f.has_animation = true;
      // Dynamic geometry when the animated node or one of its descendants carries a mesh.
      std::vector<int> stack{channel.node};
      while (!stack.empty() && !f.has_dynamic_geometry) {
        const Node& node = nodes[static_cast<size_t>(stack.back())];
        stack.pop_back();
        if (node.mesh >= 0) f.has_dynamic_geometry = true;
        stack.insert(stack.end(), node.children.begin(), node.children.end());
      }
    }
  }
  bounds(f.bounds_min, f.bounds_max);
  return f;
}

std::map<std::string, double> SceneFeatures::as_map() const {
  const glm::vec3 extent = bounds_max - bounds_min;
  return {
      {"scene.has_emissive", has_emissive ? 1.0 : 0.0},
      {"scene.has_glossy", has_glossy ? 1.0 : 0.0},
      {"scene.has_textures", has_textures ? 1.0 : 0.0},
      {"scene.has_animation", has_animation ? 1.0 : 0.0},
      {"scene.has_dynamic_geometry", has_dynamic_geometry ? 1.0 : 0.0},
      {"scene.has_point_lights", has_point_lights ? 1.0 : 0.0},
      {"scene.has_spot_lights", has_spot_lights ? 1.0 : 0.0},
      {"scene.has_directional_lights", has_directional_lights ? 1.0 : 0.0},
      {"scene.has_lights", light_count > 0 ? 1.0 : 0.0},
      {"scene.light_count", static_cast<double>(light_count)},
      {"scene.triangle_count", static_cast<double>(triangle_count)},
      {"scene.extent", static_cast<double>(glm::max(extent.x, glm::max(extent.y, extent.z)))},
      {"scene.empty", triangle_count == 0 ? 1.0 : 0.0},
  };
}

const Camera* Scene::find_camera(std::string_view camera_name) const {
  for (const Camera& camera : cameras) {
    if (camera.name == camera_name) return &camera;
  }
  return nullptr;
}

glm::mat4 view_matrix(const Camera& camera) {
  return glm::inverse(camera.world);
}

glm::mat4 projection_matrix(const Camera& camera, float viewport_aspect) {
  float aspect = camera.aspect > 0.0f ? camera.aspect : viewport_aspect;
  if (!(aspect > 0.0f) || !std::isfinite(aspect)) aspect = 1.0f;
  const float znear = camera.znear > 0.0f ? camera.znear : 0.01f;
  const float zfar = camera.zfar > znear ? camera.zfar : znear * 1e4f;
  glm::mat4 proj = glm::perspective(camera.yfov, aspect, znear, zfar);
  proj[1][1] *= -1.0f;
  return proj;
}

Camera default_camera(const Scene& scene) {
  glm::vec3 mn, mx;
  scene.bounds(mn, mx);
  const glm::vec3 center = 0.5f * (mn + mx);
  const float radius = glm::max(0.5f * glm::length(mx - mn), 1e-3f);
  Camera camera;
  camera.name = "default";
  camera.yfov = 0.8f;
  const float distance = radius / std::sin(0.5f * camera.yfov);
  const glm::vec3 eye = center + distance * glm::normalize(glm::vec3(0.0f, 0.25f, 1.0f));
  // lookAt gives the view matrix; the camera's world matrix is its inverse.
  camera.world = glm::inverse(glm::lookAt(eye, center, glm::vec3(0.0f, 1.0f, 0.0f)));
  camera.znear = glm::max(distance - radius, radius * 1e-3f) * 0.5f;
  camera.zfar = (distance + radius) * 2.0f;
  return camera;
}

}  // namespace voxgi::scene
