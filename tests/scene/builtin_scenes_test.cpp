#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/scene/builtin_scenes.hpp"
#include "engine/scene/scene_builder.hpp"

namespace voxgi::scene {
namespace {

void expect_vec3_near(glm::vec3 a, glm::vec3 b, float eps) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

TEST(BuiltinScenes, EveryNameBuilds) {
  for (const std::string& name : builtin_scene_names()) {
    const Scene scene = make_builtin_scene(name);
    EXPECT_EQ(scene.source, "builtin:" + name);
    EXPECT_NE(scene.find_camera("default"), nullptr) << name;
    EXPECT_TRUE(scene.warnings.empty()) << name;
  }
}

TEST(BuiltinScenes, UnknownNameListsValidOnes) {
  try {
    make_builtin_scene("cornel");
    FAIL() << "expected SceneError";
  } catch (const SceneError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("builtin:cornel"), std::string::npos) << message;
    for (const std::string& name : builtin_scene_names()) {
      EXPECT_NE(message.find(name), std::string::npos) << message;
    }
  }
}

TEST(BuiltinScenes, CornellBoxMatchesTheMeasuredBox) {
  const Scene scene = make_builtin_scene("cornell");
  EXPECT_EQ(scene.meshes.size(), 8u);
  EXPECT_EQ(scene.materials.size(), 4u);
  ASSERT_EQ(scene.lights.size(), 1u);
  const SceneFeatures f = scene.features();
  EXPECT_EQ(f.triangle_count, 36u);
  EXPECT_EQ(f.instance_count, 8u);
  EXPECT_TRUE(f.has_emissive);
  EXPECT_FALSE(f.has_glossy);
  EXPECT_FALSE(f.has_textures);
  EXPECT_TRUE(f.has_point_lights);
  EXPECT_FALSE(f.has_spot_lights);
  expect_vec3_near(f.bounds_min, glm::vec3(0.0f), 1e-5f);
  expect_vec3_near(f.bounds_max, glm::vec3(0.556f, 0.5488f, 0.5592f), 1e-4f);

  // Albedos and the emitter.
  bool red = false, green = false, light = false;
  for (const Material& m : scene.materials) {
    EXPECT_EQ(m.roughness, 1.0f);
    EXPECT_EQ(m.metallic, 0.0f);
    if (m.name == "red") red = glm::vec3(m.base_color) == glm::vec3(0.63f, 0.065f, 0.05f);
    if (m.name == "green") green = glm::vec3(m.base_color) == glm::vec3(0.14f, 0.45f, 0.091f);
    if (m.name == "light") light = m.emissive == glm::vec3(17.0f, 12.0f, 4.0f);
  }
  EXPECT_TRUE(red && green && light);

  // The point light: radiance × area of the 0.13 × 0.105 m quad, 1 cm below its centre.
  const Light& point = scene.lights[0];
  EXPECT_EQ(point.type, LightType::Point);
  const float area = 0.13f * 0.105f;
  expect_vec3_near(point.color * point.intensity, glm::vec3(17.0f, 12.0f, 4.0f) * area, 1e-5f);
  expect_vec3_near(point.position, glm::vec3(0.278f, 0.538f, 0.2795f), 1e-4f);

  // Red on the left seen from the camera (+X), green on the right (x = 0).
  for (const Instance& instance : scene.instances()) {
    const Primitive& p = scene.meshes[size_t(instance.mesh)].primitives[0];
    const std::string& material = scene.materials[size_t(p.material)].name;
    if (material == "red") {
      EXPECT_GT(p.bounds_min.x, 0.5f);
    }
    if (material == "green") {
      EXPECT_LT(p.bounds_max.x, 0.01f);
    }
  }

  const Camera* camera = scene.find_camera("default");
  ASSERT_NE(camera, nullptr);
  EXPECT_NEAR(camera->yfov, glm::radians(39.3f), 1e-5f);
  expect_vec3_near(glm::vec3(camera->world[3]), glm::vec3(0.278f, 0.273f, -0.8f), 1e-5f);
  const glm::vec3 forward = glm::vec3(camera->world * glm::vec4(0, 0, -1, 0));
  expect_vec3_near(forward, glm::vec3(0, 0, 1), 1e-5f);
  EXPECT_GT(camera->zfar, 1.4f);  // sees the back wall
}

TEST(BuiltinScenes, CornellWallsFaceInwards) {
  const Scene scene = make_builtin_scene("cornell");
  const glm::vec3 centre(0.278f, 0.274f, 0.28f);
  for (const Instance& instance : scene.instances()) {
    const Mesh& mesh = scene.meshes[size_t(instance.mesh)];
    if (mesh.name.find("block") != std::string::npos) continue;
    const Primitive& p = mesh.primitives[0];
    for (size_t t = 0; t < p.indices.size(); t += 3) {
      const glm::vec3 a = p.vertices[p.indices[t]].position,
                      b = p.vertices[p.indices[t + 1]].position,
                      c = p.vertices[p.indices[t + 2]].position;
      const glm::vec3 face = glm::cross(b - a, c - a);  // counter-clockwise front face
      EXPECT_GT(glm::dot(face, centre - a), 0.0f) << mesh.name;
      EXPECT_GT(glm::dot(p.vertices[p.indices[t]].normal, centre - a), 0.0f) << mesh.name;
    }
  }
}

TEST(BuiltinScenes, PlaneScenesHaveOneLightOfEachType) {
  const Scene point = make_builtin_scene("plane-point");
  const Scene spot = make_builtin_scene("plane-spot");
  const Scene directional = make_builtin_scene("plane-directional");
  ASSERT_EQ(point.lights.size(), 1u);
  ASSERT_EQ(spot.lights.size(), 1u);
  ASSERT_EQ(directional.lights.size(), 1u);
  EXPECT_EQ(point.lights[0].type, LightType::Point);
  EXPECT_EQ(point.lights[0].intensity, 10.0f);
  expect_vec3_near(point.lights[0].position, glm::vec3(0, 1, 0), 1e-6f);
  EXPECT_EQ(spot.lights[0].type, LightType::Spot);
  EXPECT_EQ(spot.lights[0].inner_cone, 0.3f);
  EXPECT_EQ(spot.lights[0].outer_cone, 0.6f);
  expect_vec3_near(spot.lights[0].direction, glm::vec3(0, -1, 0), 1e-6f);
  EXPECT_EQ(directional.lights[0].type, LightType::Directional);
  EXPECT_EQ(directional.lights[0].intensity, 2.0f);
  expect_vec3_near(directional.lights[0].direction, glm::normalize(glm::vec3(0.5f, -1, 0)), 1e-6f);

  const SceneFeatures f = spot.features();
  EXPECT_TRUE(f.has_spot_lights);
  EXPECT_FALSE(f.has_point_lights);
  EXPECT_EQ(f.triangle_count, 2u + 12u);
  expect_vec3_near(f.bounds_min, glm::vec3(-1, 0, -1), 1e-5f);
  expect_vec3_near(f.bounds_max, glm::vec3(1, 0.5f, 1), 1e-5f);
  EXPECT_EQ(point.materials[0].base_color, glm::vec4(0.8f, 0.8f, 0.8f, 1.0f));

  // The camera looks straight down at the plane.
  const Camera* camera = point.find_camera("default");
  ASSERT_NE(camera, nullptr);
  expect_vec3_near(glm::vec3(camera->world * glm::vec4(0, 0, -1, 0)), glm::vec3(0, -1, 0), 1e-5f);
}

TEST(BuiltinScenes, EmptySceneHasNoGeometry) {
  const Scene scene = make_builtin_scene("empty");
  const auto map = scene.features().as_map();
  EXPECT_EQ(map.at("scene.empty"), 1.0);
  EXPECT_EQ(map.at("scene.has_lights"), 0.0);
  EXPECT_EQ(map.at("scene.extent"), 0.0);
}

TEST(SceneFeatures, AsMapHasEveryKey) {
  const auto map = make_builtin_scene("cornell").features().as_map();
  for (const char* key :
       {"scene.has_emissive", "scene.has_glossy", "scene.has_textures", "scene.has_animation",
        "scene.has_dynamic_geometry", "scene.has_point_lights", "scene.has_spot_lights",
        "scene.has_directional_lights", "scene.has_lights", "scene.light_count",
        "scene.triangle_count", "scene.extent", "scene.empty"}) {
    EXPECT_EQ(map.count(key), 1u) << key;
  }
  EXPECT_EQ(map.size(), 13u);
  EXPECT_EQ(map.at("scene.triangle_count"), 36.0);
  EXPECT_EQ(map.at("scene.light_count"), 1.0);
  EXPECT_EQ(map.at("scene.has_emissive"), 1.0);
  EXPECT_EQ(map.at("scene.empty"), 0.0);
  EXPECT_NEAR(map.at("scene.extent"), 0.5592, 1e-4);
}

TEST(SceneFeatures, GlossyCountsOnlyUsedMaterials) {
  SceneBuilder b("glossy");
  Material shiny;
  shiny.roughness = 0.2f;
  shiny.metallic = 0.0f;
  const int unused = b.add_material(shiny);
  (void)unused;
  Material rough;
  rough.roughness = 1.0f;
  rough.metallic = 0.0f;
  b.add_quad("q", {0, 0, 0}, {1, 0, 0}, {0, 0, -1}, b.add_material(rough));
  EXPECT_FALSE(b.finish().features().has_glossy);

  SceneBuilder b2("glossy2");
  b2.add_quad("q", {0, 0, 0}, {1, 0, 0}, {0, 0, -1}, b2.add_material(shiny));
  EXPECT_TRUE(b2.finish().features().has_glossy);
}

TEST(Camera, ProjectionIsVulkanClipSpace) {
  Camera camera;
  camera.yfov = 1.0f;
  camera.znear = 0.1f;
  camera.zfar = 100.0f;
  const glm::mat4 proj = projection_matrix(camera, 2.0f);
  EXPECT_LT(proj[1][1], 0.0f);  // y down
  glm::vec4 near_point = proj * glm::vec4(0, 0, -0.1f, 1);
  glm::vec4 far_point = proj * glm::vec4(0, 0, -100.0f, 1);
  EXPECT_NEAR(near_point.z / near_point.w, 0.0f, 1e-5f);
  EXPECT_NEAR(far_point.z / far_point.w, 1.0f, 1e-5f);
  // A point above the axis lands in the upper half (negative y in Vulkan NDC).
  glm::vec4 up = proj * glm::vec4(0, 1, -5, 1);
  EXPECT_LT(up.y / up.w, 0.0f);
  // The viewport aspect is used unless the camera has its own.
  EXPECT_NEAR(proj[0][0] * 2.0f, -proj[1][1], 1e-5f);
  camera.aspect = 1.0f;
  const glm::mat4 square = projection_matrix(camera, 2.0f);
  EXPECT_NEAR(square[0][0], -square[1][1], 1e-5f);
}

TEST(Camera, DefaultCameraSeesTheBounds) {
  const Scene scene = make_builtin_scene("plane-point");
  const Camera camera = default_camera(scene);
  glm::vec3 mn, mx;
  scene.bounds(mn, mx);
  const glm::mat4 view_proj = projection_matrix(camera, 1.0f) * view_matrix(camera);
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner((i & 1) ? mx.x : mn.x, (i & 2) ? mx.y : mn.y, (i & 4) ? mx.z : mn.z);
    const glm::vec4 clip = view_proj * glm::vec4(corner, 1.0f);
    ASSERT_GT(clip.w, 0.0f);
    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
    EXPECT_LE(std::abs(ndc.x), 1.0f);
    EXPECT_LE(std::abs(ndc.y), 1.0f);
    EXPECT_GE(ndc.z, 0.0f);
    EXPECT_LE(ndc.z, 1.0f);
  }
}

TEST(SceneBuilder, BoxNormalsPointOutwards) {
  SceneBuilder b("box");
  const int node =
      b.add_box("box", {1, 2, 3}, {0.5f, 1.0f, 2.0f}, b.add_material(Material{}), 0.4f);
  const Scene scene = b.finish();
  const Node& n = scene.nodes[size_t(node)];
  const Primitive& p = scene.meshes[size_t(n.mesh)].primitives[0];
  EXPECT_EQ(p.vertices.size(), 24u);
  EXPECT_EQ(p.indices.size(), 36u);
  for (const Vertex& v : p.vertices) {
    EXPECT_GT(glm::dot(v.normal, v.position), 0.0f);  // unit cube around the origin
    EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(glm::vec3(v.tangent), v.normal), 0.0f, 1e-6f);
  }
  glm::vec3 mn, mx;
  scene.bounds(mn, mx);
  EXPECT_NEAR(0.5f * (mn.y + mx.y), 2.0f, 1e-5f);
  EXPECT_NEAR(mx.y - mn.y, 1.0f, 1e-5f);
  EXPECT_FALSE(n.matrix.has_value());  // TRS, so it can be animated
}

TEST(SceneBuilder, RejectsBadInput) {
  SceneBuilder b("bad");
  const int material = b.add_material(Material{});
  EXPECT_THROW(b.add_mesh("m", std::vector<Vertex>(3), {0, 1, 3}, material), SceneError);
  EXPECT_THROW(b.add_mesh("m", std::vector<Vertex>(3), {0, 1}, material), SceneError);
  EXPECT_THROW(b.add_mesh("m", std::vector<Vertex>(3), {0, 1, 2}, 5), SceneError);
  const int a = b.add_node("a"), c = b.add_node("c");
  b.set_parent(c, a);
  EXPECT_THROW(b.set_parent(a, c), SceneError);
  Texture texture;
  texture.width = 2;
  texture.height = 2;
  texture.pixels.resize(3);
  try {
    b.add_texture(texture);
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("builtin:bad"), std::string::npos);
  }
}

TEST(SceneBuilder, HierarchyComposesTransforms) {
  SceneBuilder b("tree");
  const int parent = b.add_node("parent", glm::translate(glm::mat4(1.0f), glm::vec3(1, 0, 0)));
  const int child =
      b.add_quad("child", {0, 0, 0}, {1, 0, 0}, {0, 0, -1}, b.add_material(Material{}));
  b.scene().nodes[size_t(child)].translation = glm::vec3(0, 2, 0);
  b.set_parent(child, parent);
  const Scene scene = b.finish();
  EXPECT_EQ(glm::vec3(scene.nodes[size_t(child)].world[3]), glm::vec3(1, 2, 0));
}

}  // namespace
}  // namespace voxgi::scene
