#include "engine/scene/builtin_scenes.hpp"

#include "engine/scene/scene_builder.hpp"

namespace voxgi::scene {

namespace {

Material diffuse(const std::string& name, glm::vec3 albedo) {
  Material m;
  m.name = name;
  m.base_color = glm::vec4(albedo, 1.0f);
  m.metallic = 0.0f;
  m.roughness = 1.0f;
  return m;
}

// The Cornell box in metres, open towards -Z, as measured (see shared/scenes/cornell-box).
Scene make_cornell() {
  SceneBuilder b("cornell");
  constexpr float width = 0.556f, height = 0.5488f, depth = 0.5592f;
  const int white = b.add_material(diffuse("white", {0.725f, 0.71f, 0.68f}));
  const int red = b.add_material(diffuse("red", {0.63f, 0.065f, 0.05f}));
  const int green = b.add_material(diffuse("green", {0.14f, 0.45f, 0.091f}));
  // A pure emitter (black base colour): the point light 1 cm below it must not light it.
  Material emitter = diffuse("light", {0.0f, 0.0f, 0.0f});
  const glm::vec3 radiance(17.0f, 12.0f, 4.0f);
  emitter.emissive = radiance;
  const int light = b.add_material(emitter);

  b.add_quad("floor", {0, 0, 0}, {0, 0, depth}, {width, 0, 0}, white);
  b.add_quad("ceiling", {0, height, 0}, {width, 0, 0}, {0, 0, depth}, white);
  b.add_quad("back_wall", {0, 0, depth}, {0, height, 0}, {width, 0, 0}, white);
  b.add_quad("green_wall", {0, 0, 0}, {0, height, 0}, {0, 0, depth}, green);
  b.add_quad("red_wall", {width, 0, 0}, {0, 0, depth}, {0, height, 0}, red);
  // Blocks: centre, footprint and turn fitted to the measured corner coordinates.
  b.add_box("short_block", {0.1855f, 0.0825f, 0.169f}, {0.167f, 0.165f, 0.165f}, white, -0.297f);
  b.add_box("tall_block", {0.3685f, 0.165f, 0.35125f}, {0.165f, 0.33f, 0.166f}, white, 0.300f);

  // The ceiling light: a 0.13 × 0.105 m emitter facing down, just below the ceiling.
  const glm::vec3 light_min(0.213f, 0.548f, 0.227f);
  const glm::vec2 light_size(0.13f, 0.105f);
  b.add_quad("light", light_min, {light_size.x, 0, 0}, {0, 0, light_size.y}, light);

  // A point light with the same on-axis intensity as the area light (I = L × A), 1 cm below
  // its centre, for techniques that only take punctual lights.
  Light point;
  point.name = "ceiling_point";
  point.type = LightType::Point;
  const float area = light_size.x * light_size.y;
  point.color = radiance / radiance.x;
  point.intensity = radiance.x * area;
  const glm::vec3 centre = light_min + glm::vec3(0.5f * light_size.x, 0, 0.5f * light_size.y);
  b.add_light(point, centre - glm::vec3(0, 0.01f, 0));

  b.add_camera("default", {0.278f, 0.273f, -0.8f}, {0.278f, 0.273f, 0.0f}, glm::radians(39.3f));
  return b.finish();
}

// A 2 × 2 m floor with a small occluder and one light of `type`, seen from above.
Scene make_plane(const std::string& name, LightType type) {
  SceneBuilder b(name);
  const int floor = b.add_material(diffuse("floor", glm::vec3(0.8f)));
  b.add_quad("floor", {-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, floor);
  // Placed so that its shadow falls inside the spot cone and, seen from the camera above, is
  // not hidden under the box itself.
  b.add_box("occluder", {0.25f, 0.4f, 0.0f}, glm::vec3(0.2f), floor);
  Light light;
  light.type = type;
  light.name = name + "_light";
  if (type == LightType::Directional) {
    light.intensity = 2.0f;  // lux
  } else {
    light.intensity = 10.0f;  // candela
  }
  if (type == LightType::Spot) {
    light.inner_cone = 0.3f;
    light.outer_cone = 0.6f;
  }
  // The directional light comes in obliquely so that its shadow is not right under the box.
  const glm::vec3 direction = type == LightType::Directional
                                  ? glm::normalize(glm::vec3(0.5f, -1.0f, 0.0f))
                                  : glm::vec3(0.0f, -1.0f, 0.0f);
  b.add_light(light, {0, 1, 0}, direction);
  b.add_camera("default", {0, 3, 0}, {0, 0, 0}, 0.75f, {0, 0, -1});
  return b.finish();
}

Scene make_empty() {
  SceneBuilder b("empty");
  b.add_camera("default", {0, 0, 5}, {0, 0, 0}, 0.8f);
  return b.finish();
}

}  // namespace

std::vector<std::string> builtin_scene_names() {
  return {"cornell", "plane-point", "plane-spot", "plane-directional", "empty"};
}

Scene make_builtin_scene(std::string_view name) {
  if (name == "cornell") return make_cornell();
  if (name == "plane-point") return make_plane("plane-point", LightType::Point);
  if (name == "plane-spot") return make_plane("plane-spot", LightType::Spot);
  if (name == "plane-directional") return make_plane("plane-directional", LightType::Directional);
  if (name == "empty") return make_empty();
  std::string valid;
  for (const std::string& n : builtin_scene_names()) valid += (valid.empty() ? "" : ", ") + n;
  throw SceneError("builtin:" + std::string(name) +
                   ": name: unknown built-in scene; expected one of " + valid);
}

}  // namespace voxgi::scene
