#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/scene/scene_builder.hpp"

namespace voxgi::scene {
namespace {

Scene animated_scene(AnimationPath path, Interpolation interpolation, std::vector<float> times,
                     std::vector<glm::vec4> values) {
  SceneBuilder b("animated");
  const int node = b.add_box("box", {0, 0, 0}, glm::vec3(1), b.add_material(Material{}));
  Animation animation;
  animation.name = "move";
  AnimationChannel channel;
  channel.node = node;
  channel.path = path;
  channel.interpolation = interpolation;
  channel.times = std::move(times);
  channel.values = std::move(values);
  animation.duration = channel.times.back();
  animation.channels.push_back(channel);
  b.scene().animations.push_back(animation);
  b.scene().nodes[size_t(node)].animated = true;
  return b.finish();
}

TEST(Animation, LinearTranslation) {
  Scene scene = animated_scene(AnimationPath::Translation, Interpolation::Linear, {0.0f, 1.0f},
                               {glm::vec4(0, 0, 0, 0), glm::vec4(2, 4, 0, 0)});
  EXPECT_TRUE(scene.animate(0.5));
  EXPECT_EQ(scene.nodes[0].translation, glm::vec3(1, 2, 0));
  EXPECT_EQ(glm::vec3(scene.nodes[0].world[3]), glm::vec3(1, 2, 0));
  EXPECT_EQ(glm::vec3(scene.instances()[0].world[3]), glm::vec3(1, 2, 0));
  EXPECT_FALSE(scene.animate(0.5));  // nothing moved since
  EXPECT_TRUE(scene.animate(1.25));  // loops: 0.25
  EXPECT_NEAR(scene.nodes[0].translation.x, 0.5f, 1e-6f);
  const SceneFeatures f = scene.features();
  EXPECT_TRUE(f.has_animation);
  EXPECT_TRUE(f.has_dynamic_geometry);
}

TEST(Animation, Step) {
  Scene scene =
      animated_scene(AnimationPath::Scale, Interpolation::Step, {0.0f, 1.0f, 2.0f},
                     {glm::vec4(1, 1, 1, 0), glm::vec4(2, 2, 2, 0), glm::vec4(3, 3, 3, 0)});
  scene.animate(0.99);
  EXPECT_EQ(scene.nodes[0].scale, glm::vec3(1));
  scene.animate(1.5);
  EXPECT_EQ(scene.nodes[0].scale, glm::vec3(2));
}

TEST(Animation, RotationSlerp) {
  // 0 → 180° about +Y (quaternions x, y, z, w); halfway is 90°.
  Scene scene = animated_scene(AnimationPath::Rotation, Interpolation::Linear, {0.0f, 2.0f},
                               {glm::vec4(0, 0, 0, 1), glm::vec4(0, 1, 0, 0)});
  scene.animate(1.0);
  const glm::vec3 x = glm::vec3(scene.nodes[0].world * glm::vec4(1, 0, 0, 0));
  EXPECT_NEAR(x.x, 0.0f, 1e-5f);
  EXPECT_NEAR(x.z, -1.0f, 1e-5f);  // +X turned 90° about +Y lands on -Z
  EXPECT_NEAR(glm::length(scene.nodes[0].rotation), 1.0f, 1e-5f);
}

TEST(Animation, CubicSplineHitsKeys) {
  // in-tangent, value, out-tangent per key.
  Scene scene = animated_scene(AnimationPath::Translation, Interpolation::CubicSpline, {0.0f, 1.0f},
                               {glm::vec4(0), glm::vec4(0, 0, 0, 0), glm::vec4(1, 0, 0, 0),
                                glm::vec4(1, 0, 0, 0), glm::vec4(1, 0, 0, 0), glm::vec4(0)});
  scene.animate(0.0);
  EXPECT_NEAR(scene.nodes[0].translation.x, 0.0f, 1e-6f);
  scene.animate(0.5);
  EXPECT_NEAR(scene.nodes[0].translation.x, 0.5f, 1e-6f);  // tangents 1 make it linear
  scene.animate(0.999999);
  EXPECT_NEAR(scene.nodes[0].translation.x, 1.0f, 1e-4f);
}

TEST(Animation, LightsFollowTheirNodes) {
  SceneBuilder b("light");
  Light light;
  light.type = LightType::Spot;
  const int node = b.add_light(light, {0, 1, 0}, {0, -1, 0});
  Animation animation;
  AnimationChannel channel;
  channel.node = node;
  channel.times = {0.0f, 1.0f};
  channel.values = {glm::vec4(0, 1, 0, 0), glm::vec4(0, 3, 0, 0)};
  animation.channels.push_back(channel);
  animation.duration = 1.0f;
  b.scene().animations.push_back(animation);
  Scene scene = b.finish();
  scene.animate(0.5);
  EXPECT_EQ(scene.lights[0].position, glm::vec3(0, 2, 0));
  EXPECT_NEAR(scene.lights[0].direction.y, -1.0f, 1e-6f);
  EXPECT_FALSE(scene.features().has_dynamic_geometry);
}

TEST(NegativeScale, InstanceIsMirrored) {
  SceneBuilder b("mirror");
  const int material = b.add_material(Material{});
  b.add_box("normal", {0, 0, 0}, glm::vec3(1), material);
  const int mirrored = b.add_quad("mirrored", {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, material);
  b.scene().nodes[size_t(mirrored)].scale = glm::vec3(-1, 1, 1);
  const Scene scene = b.finish();
  const auto instances = scene.instances();
  ASSERT_EQ(instances.size(), 2u);
  EXPECT_FALSE(instances[0].mirrored);
  EXPECT_TRUE(instances[1].mirrored);
}

}  // namespace
}  // namespace voxgi::scene
