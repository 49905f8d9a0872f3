#include "tests/common/hard_case_scenes.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <vector>

#include "engine/scene/scene_builder.hpp"

namespace voxgi::test {

using scene::Light;
using scene::LightType;
using scene::Material;
using scene::SceneBuilder;

Material matte(glm::vec3 albedo, glm::vec3 emissive) {
  Material m;
  m.name = "matte";
  m.base_color = glm::vec4(albedo, 1.0f);
  m.metallic = 0.0f;
  m.roughness = 1.0f;
  m.emissive = emissive;
  return m;
}

Light point_light(float intensity) {
  Light light;
  light.type = LightType::Point;
  light.intensity = intensity;
  return light;
}

void add_closed_box(SceneBuilder& builder, glm::vec3 lo, glm::vec3 hi, float thickness,
                    int material) {
  const glm::vec3 c = 0.5f * (lo + hi);
  const glm::vec3 size = hi - lo + glm::vec3(2.0f * thickness);
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      glm::vec3 centre = c;
      centre[axis] = side == 0 ? lo[axis] - 0.5f * thickness : hi[axis] + 0.5f * thickness;
      glm::vec3 extent = size;
      extent[axis] = thickness;
      builder.add_box("wall", centre, extent, material);
    }
  }
}

scene::Scene lit_floor(const std::string& name, glm::vec3 offset, float scale, glm::vec3 eye,
                       const char* camera, const Material& surface) {
  SceneBuilder b(name);
  const int white = b.add_material(surface);
  b.add_quad("floor", offset + glm::vec3(-1, 0, -1) * scale, glm::vec3(0, 0, 2) * scale,
             glm::vec3(2, 0, 0) * scale, white);
  b.add_box("box", offset + glm::vec3(0.3f, 0.2f, 0.0f) * scale, glm::vec3(0.4f) * scale, white);
  b.add_light(point_light(10.0f * scale * scale), offset + glm::vec3(0, 1, 0) * scale);
  b.add_camera(camera, offset + eye * scale, offset, 0.8f);
  return b.finish();
}

scene::Scene degenerate_triangles(const Material& surface) {
  SceneBuilder b("degenerate");
  const int white = b.add_material(surface);
  std::vector<scene::Vertex> v(9);
  // zero area (repeated vertex), collinear, and a proper triangle; all normals zero
  const glm::vec3 p[9] = {{0, 0, 0}, {0, 0, 0},   {1, 0, 0},  {0, 0, 0}, {0.5f, 0, 0},
                          {1, 0, 0}, {-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}};
  for (int i = 0; i < 9; ++i) {
    v[i].position = p[i];
    v[i].normal = glm::vec3(0.0f);
  }
  b.add_mesh("bad", v, {0, 1, 2, 3, 4, 5, 6, 7, 8}, white);
  b.add_light(point_light(5.0f), {0, 1, 0});
  b.add_camera("top", {0, 3, 0.01f}, {0, 0, 0}, 0.8f);
  return b.finish();
}

scene::Scene thin_wall(const Material& surface) {
  SceneBuilder b("thin_wall");
  const int white = b.add_material(surface);
  b.add_quad("floor", {-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, white);
  b.add_quad("wall_minus_x", {0, 0, -1}, {0, 0, 2}, {0, 1, 0}, white);
  b.add_quad("wall_plus_x", {0.001f, 0, -1}, {0, 1, 0}, {0, 0, 2}, white);
  b.add_light(point_light(5.0f), {-0.5f, 0.6f, 0});
  b.add_camera("top", {0.5f, 2.5f, 0.01f}, {0, 0, 0}, 0.9f);
  return b.finish();
}

scene::Scene light_on_a_surface_and_inside_geometry() {
  SceneBuilder b("light_on_surface");
  const int white = b.add_material(matte(glm::vec3(0.8f)));
  b.add_quad("floor", {-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, white);
  b.add_box("box", {0.3f, 0.2f, 0}, glm::vec3(0.4f), white);
  b.add_light(point_light(10.0f), {0, 0, 0});        // exactly on the floor
  b.add_light(point_light(10.0f), {0.3f, 0.2f, 0});  // inside the box
  b.add_camera("top", {0, 3, 0.01f}, {0, 0, 0}, 0.8f);
  return b.finish();
}

scene::Scene very_bright_and_very_dim_emitters() {
  SceneBuilder b("emitters");
  const int bright = b.add_material(matte(glm::vec3(0.5f), glm::vec3(1e5f)));
  const int dim = b.add_material(matte(glm::vec3(0.5f), glm::vec3(1e-5f)));
  b.add_quad("bright", {-1, 0, -1}, {0, 0, 2}, {1, 0, 0}, bright);
  b.add_quad("dim", {0, 0, -1}, {0, 0, 2}, {1, 0, 0}, dim);
  b.add_camera("top", {0, 3, 0.01f}, {0, 0, 0}, 0.8f);
  return b.finish();
}

scene::Scene camera_inside_geometry() {
  SceneBuilder b("inside");
  const int white = b.add_material(matte(glm::vec3(0.8f)));
  b.add_box("room", {0, 0, 0}, glm::vec3(2.0f), white);
  b.add_light(point_light(5.0f), {0.5f, 0.5f, 0.5f});
  b.add_camera("inside", {0, 0, 0}, {0, 0, 1}, 1.0f);
  return b.finish();
}

scene::Scene grazing_light() {
  SceneBuilder b("grazing");
  const int white = b.add_material(matte(glm::vec3(0.8f)));
  b.add_quad("floor", {-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, white);
  Light sun;
  sun.type = LightType::Directional;
  sun.intensity = 3.0f;
  b.add_light(sun, {0, 1, 0}, glm::normalize(glm::vec3(1.0f, -1e-4f, 0.0f)));
  b.add_camera("grazing", {-2, 1e-3f, 0}, {2, 0, 0}, 0.8f);
  return b.finish();
}

scene::Scene mirrored_node() {
  SceneBuilder b("mirrored");
  const int white = b.add_material(matte(glm::vec3(0.8f)));
  std::vector<scene::Vertex> v(3);
  v[0].position = {-1, 0, -1};
  v[1].position = {-1, 0, 1};
  v[2].position = {1, 0, 1};
  b.add_mesh("mirrored", v, {0, 1, 2}, white, glm::scale(glm::mat4(1.0f), {-1, 1, 1}));
  b.add_light(point_light(5.0f), {0, 1, 0});
  b.add_camera("top", {0, 3, 0.01f}, {0, 0, 0}, 0.8f);
  return b.finish();
}

}  // namespace voxgi::test
