// common.voxelize on the hard cases of HARD-CASES.md that concern voxelization.

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "engine/scene/builtin_scenes.hpp"
#include "engine/scene/scene_builder.hpp"
#include "tests/common/voxel_test_support.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

using VoxelHardCasesTest = GpuTest;

void expect_all_finite(const VoxelVolumes& v, const char* what) {
  size_t bad = 0;
  for (const std::vector<glm::vec4>* volume : {&v.albedo, &v.normal, &v.emission}) {
    for (const glm::vec4& t : *volume) {
      for (int c = 0; c < 4; ++c) bad += !std::isfinite(t[c]) || t[c] < -1.0001f;
    }
  }
  EXPECT_EQ(bad, 0u) << what << ": NaN, Inf or out-of-range values";
}

size_t occupied_count(const VoxelVolumes& v) {
  size_t n = 0;
  for (const glm::vec4& t : v.normal) n += t.w > 0.5f;
  return n;
}

scene::Vertex vertex(glm::vec3 p) {
  scene::Vertex v;
  v.position = p;
  return v;
}

TEST_F(VoxelHardCasesTest, DegenerateTrianglesAndZeroNormalsGiveNoNaNAndNoVoxels) {
  scene::SceneBuilder b("degenerate");
  const int mat = b.add_material(diffuse({0.5f, 0.5f, 0.5f}));
  // One good triangle near x = 0; zero-area ones near x = 1: repeated vertices, collinear
  // vertices, one point.
  const std::vector<scene::Vertex> vertices = {
      vertex({0.0f, 0.0f, 0.0f}), vertex({0.3f, 0.0f, 0.0f}), vertex({0.0f, 0.3f, 0.1f}),
      vertex({1.0f, 0.5f, 0.5f}), vertex({1.0f, 0.5f, 0.5f}), vertex({1.0f, 0.9f, 0.5f}),
      vertex({0.8f, 0.2f, 0.2f}), vertex({0.9f, 0.3f, 0.3f}), vertex({1.0f, 0.4f, 0.4f}),
      vertex({0.9f, 0.9f, 0.9f})};
  const std::vector<uint32_t> indices = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 9, 9};
  b.add_mesh("mixed", vertices, indices, mat);
  scene::Scene scene = b.finish();
  for (scene::Vertex& v : scene.meshes[0].primitives[0].vertices) v.normal = glm::vec3(0.0f);
  VoxelRun run(scene, {{"voxel.resolution", "16"}});
  run.render(glm::vec3(0.0f));
  const VoxelVolumes v = run.read();
  expect_all_finite(v, "degenerate");
  // Voxels wholly below x = 0.6 m hold the good triangle; the zero-area ones lie beyond.
  const double split = v.window_coord(0, glm::dvec3(0.6)).x;
  size_t near_good = 0, near_degenerate = 0;
  for (int z = 0; z < 16; ++z) {
    for (int y = 0; y < 16; ++y) {
      for (int x = 0; x < 16; ++x) {
        if (!v.occupied(0, {x, y, z})) continue;
        (x + 1 <= split ? near_good : near_degenerate) += 1;
        const glm::vec4 n = v.normal[v.texel(0, {x, y, z})];
        // Zero vertex normals fall back to the face normal: unit length, not zero.
        EXPECT_NEAR(glm::length(glm::vec3(n)), 1.0f, 1e-2f);
      }
    }
  }
  EXPECT_GT(near_good, 0u);
  EXPECT_EQ(near_degenerate, 0u) << "zero-area triangles must not create voxels";
}

TEST_F(VoxelHardCasesTest, ThinWallNormalsCancelToZeroWithoutNaN) {
  scene::SceneBuilder b("thin wall");
  const int mat = b.add_material(diffuse({0.7f, 0.7f, 0.7f}));
  // Faces 1 mm apart, facing away from each other, inside one layer of 0.1 m voxels.
  b.add_quad("front", {0.0f, 0.0f, 0.0502f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, mat);
  b.add_quad("back", {0.0f, 0.0f, 0.0512f}, {0.0f, 1.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, mat);
  VoxelRun run(b.finish(), {{"voxel.resolution", "16"}, {"voxelize.voxel_size", "0.1"}});
  run.render(glm::vec3(0.0f));
  const VoxelVolumes v = run.read();
  expect_all_finite(v, "thin wall");
  size_t count = 0;
  float longest = 0.0f;
  for (size_t i = 0; i < v.normal.size(); ++i) {
    if (v.normal[i].w < 0.5f) continue;
    ++count;
    longest = std::max(longest, glm::length(glm::vec3(v.normal[i])));
    EXPECT_NEAR(v.albedo[i].a, 1.0f, 1e-6f);
  }
  std::printf("[thin wall] %zu voxels, longest averaged normal %.4f\n", count, double(longest));
  EXPECT_GE(count, 100u);
  EXPECT_LT(longest, 0.01f) << "opposite faces in one voxel average to a zero normal";
}

TEST_F(VoxelHardCasesTest, VeryBrightAndVeryDimEmittersStayFiniteAndUnclipped) {
  scene::SceneBuilder b("emitters");
  const float strengths[3] = {1e5f, 1e4f, 1e-5f};
  for (int i = 0; i < 3; ++i) {
    scene::Material m = diffuse({0.0f, 0.0f, 0.0f});
    m.emissive = glm::vec3(strengths[i]);
    b.add_quad("emitter", {float(i), 0.0f, 0.05f}, {0.5f, 0.0f, 0.0f}, {0.0f, 0.5f, 0.0f},
               b.add_material(m));
  }
  VoxelRun run(b.finish(), {{"voxel.resolution", "32"}, {"voxelize.voxel_size", "0.1"}});
  run.render(glm::vec3(0.0f));
  const VoxelVolumes v = run.read();
  expect_all_finite(v, "emitters");
  for (int i = 0; i < 3; ++i) {
    // The voxel at the quad's centre.
    const glm::ivec3 w =
        glm::ivec3(glm::floor(v.window_coord(0, glm::dvec3(float(i) + 0.25f, 0.25f, 0.05f))));
    const float e = v.emission[v.texel(0, w)].x;
    std::printf("[emitter %g] voxel emission %g\n", double(strengths[i]), double(e));
    ASSERT_TRUE(v.occupied(0, w));
    if (i == 0) {
      EXPECT_FLOAT_EQ(e, 65504.0f) << "clamped to the half-float maximum, never Inf";
    } else {
      EXPECT_NEAR(e, strengths[i], strengths[i] * 0.01f) << "neither clipped nor rounded to 0";
    }
  }
}

TEST_F(VoxelHardCasesTest, FarFromOriginAndTinyScenesHaveNoHoles) {
  check_coverage("offset 1e5 m",
                 random_scene(1, glm::translate(glm::mat4(1.0f), glm::vec3(1e5f, -1e5f, 1e5f))),
                 {{"voxelize.conservative", "geometry_shader"}});
  check_coverage("1 mm scene", random_scene(2, glm::scale(glm::mat4(1.0f), glm::vec3(1e-3f))),
                 {{"voxelize.conservative", "geometry_shader"}});
}

TEST_F(VoxelHardCasesTest, EmptySceneGivesEmptyValidVolumes) {
  for (const char* levels : {"1", "3"}) {
    VoxelRun run(scene::make_builtin_scene("empty"),
                 {{"voxel.resolution", "16"}, {"voxel.levels", levels}});
    run.render(glm::vec3(0.0f));
    const VoxelVolumes v = run.read();
    expect_all_finite(v, "empty");
    EXPECT_EQ(occupied_count(v), 0u);
    for (uint32_t l = 0; l < v.levels; ++l) {
      EXPECT_EQ(v.info.levels[l].origin_voxel.w, 1);
      EXPECT_GT(v.info.levels[l].min_corner_size.w, 0.0f);
    }
    run.render(glm::vec3(0.0f));
    EXPECT_FALSE(run.last_skip_reason().empty()) << "nothing moved";
  }
}

// A static floor and a box that flies along x through and out of the windows, 0.6 m (about
// five level-0 voxels) per frame.
scene::Scene moving_box_scene() {
  scene::SceneBuilder b("moving box");
  const int floor = b.add_material(diffuse({0.8f, 0.8f, 0.8f}));
  scene::Material red = diffuse({0.9f, 0.1f, 0.1f});
  red.emissive = glm::vec3(3.0f, 0.0f, 0.0f);
  const int box = b.add_material(red);
  b.add_quad("floor", {-3.0f, -0.5f, 3.0f}, {6.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -6.0f}, floor);
  const int node = b.add_box("mover", {0.0f, 0.0f, 0.0f}, {0.4f, 0.4f, 0.4f}, box, 0.3f);
  scene::Scene& s = b.scene();
  s.nodes[size_t(node)].animated = true;
  scene::Animation anim;
  anim.name = "fly";
  scene::AnimationChannel channel;
  channel.node = node;
  channel.path = scene::AnimationPath::Translation;
  channel.times = {0.0f, 1.0f};
  channel.values = {glm::vec4(-3.0f, 0.0f, 0.2f, 0.0f), glm::vec4(3.0f, 0.3f, -0.2f, 0.0f)};
  anim.channels.push_back(channel);
  anim.duration = 1.0f;
  s.animations.push_back(anim);
  return b.finish();
}

class VoxelMovingObjectTest : public GpuTest, public ::testing::WithParamInterface<const char*> {};

// The scratch buffer transient (cleared every frame) and persistent (kept clean by the resolve).
INSTANTIATE_TEST_SUITE_P(ScratchLifetime, VoxelMovingObjectTest,
                         ::testing::Values("tests/common/graphs/voxelize.json",
                                           "tests/common/graphs/voxelize_persistent_scratch.json"));

TEST_P(VoxelMovingObjectTest, MovingObjectLeavesNoStaleVoxels) {
  const scene::Scene scene = moving_box_scene();
  ASSERT_TRUE(scene.features().has_dynamic_geometry);
  const std::map<std::string, std::string> params = {{"voxel.resolution", "16"},
                                                     {"voxel.levels", "2"},
                                                     {"voxelize.voxel_size", "0.125"},
                                                     {"voxelize.center", "camera"}};
  VoxelRun moving(scene, params, GetParam());
  const glm::vec3 camera(0.1f, 0.0f, 0.0f);
  for (int frame = 0; frame <= 10; ++frame) {
    const double t = 0.095 * frame;
    moving.animate(t);
    moving.render(camera, frame > 0);
    const double moving_ms = moving.last_gpu_ms();
    VoxelRun fresh(scene, params, GetParam());
    fresh.animate(t);
    fresh.render(camera, true);
    const VoxelVolumes a = moving.read(), b = fresh.read();
    size_t different = 0, occupied = 0;
    for (size_t i = 0; i < a.normal.size(); ++i) {
      occupied += a.normal[i].w > 0.5f;
      different += std::memcmp(&a.albedo_bytes[i * 4], &b.albedo_bytes[i * 4], 4) != 0 ||
                   std::memcmp(&a.normal_bytes[i * 8], &b.normal_bytes[i * 8], 8) != 0 ||
                   std::memcmp(&a.emission_bytes[i * 8], &b.emission_bytes[i * 8], 8) != 0;
    }
    std::printf(
        "[moving box t=%.3f] %zu occupied, %zu differ from a full revoxelization; "
        "incremental %.2f ms, full %.2f ms\n",
        t, occupied, different, moving_ms, fresh.last_gpu_ms());
    EXPECT_EQ(different, 0u) << "frame " << frame;
  }
  // Nothing moves: the pass skips.
  moving.render(camera, false);
  EXPECT_EQ(moving.last_skip_reason(), "static voxels up to date, window unchanged");
}

}  // namespace
}  // namespace voxgi::test
