// What a voxel holds (docs/voxelization.md): emission weighted by the part of the voxel's
// cross-section its surfaces cover, and stacked surfaces that face the same way showing only
// the front one. Voxel edges are 1 m and the anchor is snapped to even metres, so integer
// world coordinates are voxel faces.

#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "engine/scene/scene_builder.hpp"
#include "tests/common/voxel_test_support.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

using VoxelSurfacesTest = GpuTest;

const std::map<std::string, std::string> kOneMetreVoxels = {
    {"voxel.resolution", "8"}, {"voxelize.voxel_size", "1"}, {"voxelize.center", "scene"}};

scene::Material emitter(glm::vec3 albedo, glm::vec3 radiance) {
  scene::Material m = diffuse(albedo);
  m.double_sided = false;
  m.emissive = radiance;
  return m;
}

struct VoxelValue {
  glm::vec4 albedo, normal, emission;
};

VoxelValue voxel_at(const VoxelVolumes& v, const glm::dvec3& world) {
  const glm::ivec3 w = glm::ivec3(glm::floor(v.window_coord(0, world)));
  const size_t t = v.texel(0, w);
  return {v.albedo[t], v.normal[t], v.emission[t]};
}

// A ceiling (white, facing down) with a light fixture 5 cm under it (black, emitting, facing
// down), both covering the voxels x, z in [2, 6) of the layer y in [4, 5); a floor far below
// keeps the scene bounds symmetric.
scene::Scene ceiling_with_fixture() {
  scene::SceneBuilder b("fixture");
  const int white = b.add_material(emitter({0.8f, 0.8f, 0.8f}, glm::vec3(0.0f)));
  const int light = b.add_material(emitter({0.0f, 0.0f, 0.0f}, {10.0f, 5.0f, 2.0f}));
  b.add_quad("ceiling", {2, 4.5f, 2}, {4, 0, 0}, {0, 0, 4}, white);
  b.add_quad("fixture", {2, 4.45f, 2}, {4, 0, 0}, {0, 0, 4}, light);
  b.add_quad("floor", {2, 1.5f, 2}, {0, 0, 4}, {4, 0, 0}, white);
  return b.finish();
}

TEST_F(VoxelSurfacesTest, StackedSurfacesShowTheFrontOne) {
  const scene::Scene scene = ceiling_with_fixture();
  for (const char* mode : {"front", "average"}) {
    std::map<std::string, std::string> params = kOneMetreVoxels;
    params["voxelize.stacked_surfaces"] = mode;
    std::vector<uint8_t> first;
    for (int run_index = 0; run_index < 2; ++run_index) {
      VoxelRun run(scene, params);
      run.render(glm::vec3(4.0f));
      const VoxelVolumes v = run.read();
      const VoxelValue inside = voxel_at(v, {3.5, 4.5, 4.5});
      std::printf("[%s] emission %.3f %.3f %.3f, albedo %.3f, normal y %.3f, opacity %.3f\n", mode,
                  inside.emission.x, inside.emission.y, inside.emission.z, inside.albedo.x,
                  inside.normal.y, inside.albedo.a);
      ASSERT_GT(inside.normal.w, 0.5f) << "the fixture's voxel is empty";
      const float share = std::string(mode) == "front" ? 1.0f : 0.5f;
      EXPECT_NEAR(inside.emission.x, 10.0f * share, 0.02f) << mode;
      EXPECT_NEAR(inside.emission.y, 5.0f * share, 0.01f) << mode;
      EXPECT_NEAR(inside.emission.z, 2.0f * share, 0.005f) << mode;
      EXPECT_NEAR(inside.albedo.x, 0.8f * (1.0f - share), 2.0f / 255.0f) << mode;
      EXPECT_NEAR(inside.albedo.a, 1.0f, 1e-3f) << "hiding a surface must not open the voxel";
      EXPECT_NEAR(inside.normal.y, -1.0f, 1e-3f);
      // The floor faces up alone: untouched by the rule.
      const VoxelValue floor = voxel_at(v, {3.5, 1.5, 4.5});
      EXPECT_NEAR(floor.albedo.x, 0.8f, 2.0f / 255.0f) << mode;
      // The keys are combined by atomicMax, so fragment order cannot change the result.
      if (run_index == 0) {
        first = v.emission_bytes;
      } else {
        EXPECT_TRUE(first == v.emission_bytes) << mode << ": emission differs between runs";
      }
    }
  }
}

// Surfaces that face each other in one voxel (the two faces of a thin wall) both count, and so
// do coplanar pieces of different objects (tiles meeting in a voxel).
TEST_F(VoxelSurfacesTest, FacingAwayAndCoplanarSurfacesAreNotHidden) {
  scene::SceneBuilder b("tiles");
  const int red = b.add_material(emitter({0.8f, 0.0f, 0.0f}, {4.0f, 0.0f, 0.0f}));
  const int blue = b.add_material(emitter({0.0f, 0.0f, 0.8f}, {0.0f, 0.0f, 4.0f}));
  // Two tiles of a floor at y = 2.5 meeting at x = 4.5, inside voxel x in [4, 5).
  b.add_quad("tile_a", {2, 2.5f, 2}, {0, 0, 4}, {2.5f, 0, 0}, red);
  b.add_quad("tile_b", {4.5f, 2.5f, 2}, {0, 0, 4}, {1.5f, 0, 0}, blue);
  // A thin wall: faces 2 cm apart at x = 3.49 (facing -x) and 3.51 (facing +x), above the floor.
  b.add_quad("wall_west", {3.49f, 4, 2}, {0, 0, 4}, {0, 2, 0}, red);
  b.add_quad("wall_east", {3.51f, 4, 2}, {0, 2, 0}, {0, 0, 4}, blue);
  const scene::Scene scene = b.finish();
  VoxelRun run(scene, kOneMetreVoxels);
  run.render(glm::vec3(4.0f));
  const VoxelVolumes v = run.read();

  const VoxelValue seam = voxel_at(v, {4.5, 2.5, 3.5});
  std::printf("tile seam: emission %.3f %.3f %.3f\n", seam.emission.x, seam.emission.y,
              seam.emission.z);
  EXPECT_NEAR(seam.emission.x, 2.0f, 0.01f) << "half the voxel is the red tile";
  EXPECT_NEAR(seam.emission.z, 2.0f, 0.01f) << "half the voxel is the blue tile";

  const VoxelValue wall = voxel_at(v, {3.5, 4.5, 3.5});
  std::printf("thin wall: emission %.3f %.3f %.3f, normal length %.3f\n", wall.emission.x,
              wall.emission.y, wall.emission.z, glm::length(glm::vec3(wall.normal)));
  EXPECT_GT(wall.emission.x, 1.0f) << "the face towards -x was hidden";
  EXPECT_GT(wall.emission.z, 1.0f) << "the face towards +x was hidden";
}

// A plane lying exactly on the face between two voxel layers fills the layer in front of it
// (where its normal points) and not the one behind, as a plane a hair in front of the face
// would: a floor at y = 2 facing up fills y in [2, 3), a ceiling at y = 6 facing down fills
// y in [5, 6), a wall at x = 2 facing +x fills x in [2, 3). Walls at the world's origin lie on a
// face at every voxel size (the grid is anchored on it), so this decides how thick most floors
// are.
TEST_F(VoxelSurfacesTest, PlaneOnAVoxelFaceFillsTheLayerInFrontOfIt) {
  scene::SceneBuilder b("faces");
  const int white = b.add_material(emitter({0.8f, 0.8f, 0.8f}, glm::vec3(0.0f)));
  b.add_quad("floor", {2, 2, 2}, {0, 0, 4}, {4, 0, 0}, white);
  b.add_quad("ceiling", {2, 6, 2}, {4, 0, 0}, {0, 0, 4}, white);
  b.add_quad("wall", {2, 2, 2}, {0, 4, 0}, {0, 0, 4}, white);
  const scene::Scene scene = b.finish();
  // The hardware and geometry-shader coverage run the same overlap test in the fragment shader.
  for (const char* mode : {"auto", "geometry_shader"}) {
    std::map<std::string, std::string> params = kOneMetreVoxels;
    params["voxelize.conservative"] = mode;
    VoxelRun run(scene, params);
    run.render(glm::vec3(4.0f));
    const VoxelVolumes v = run.read();
    auto occupied = [&](glm::dvec3 world) {
      return v.occupied(0, glm::ivec3(glm::floor(v.window_coord(0, world))));
    };
    for (double z : {2.5, 3.5, 5.5}) {
      for (double x : {3.5, 4.5}) {
        EXPECT_TRUE(occupied({x, 2.5, z})) << mode << ": floor's layer in front, x " << x;
        EXPECT_FALSE(occupied({x, 1.5, z})) << mode << ": floor's layer behind, x " << x;
        EXPECT_TRUE(occupied({x, 5.5, z})) << mode << ": ceiling's layer in front, x " << x;
        EXPECT_FALSE(occupied({x, 6.5, z})) << mode << ": ceiling's layer behind, x " << x;
      }
      EXPECT_TRUE(occupied({2.5, 3.5, z})) << mode << ": wall's layer in front";
      EXPECT_FALSE(occupied({1.5, 3.5, z})) << mode << ": wall's layer behind";
    }
    // The plane lies on the front voxel's face, half a voxel below its centre (the normal
    // volume's w holds 1 + d / 4 for a plane d voxels from the centre along the normal).
    const glm::ivec3 floor_voxel = glm::ivec3(glm::floor(v.window_coord(0, {4.5, 2.5, 3.5})));
    EXPECT_NEAR((v.normal[v.texel(0, floor_voxel)].w - 1.0f) / 0.25f, -0.5f, 0.01f) << mode;
  }
}

// A voxel an emitter covers in part emits that part of the emitter's light; its albedo,
// opacity, normal and plane are those of the surface.
TEST_F(VoxelSurfacesTest, EdgeVoxelsSendOutTheCoveredPart) {
  scene::SceneBuilder b("edge");
  const int lamp = b.add_material(emitter({0.6f, 0.6f, 0.6f}, {8.0f, 8.0f, 8.0f}));
  // Facing up at y = 3.5, covering x in [2, 4.25), z in [2, 6): voxel x in [4, 5) a quarter.
  b.add_quad("lamp", {2, 3.5f, 2}, {0, 0, 4}, {2.25f, 0, 0}, lamp);
  // A triangle over voxel x, z in [5, 6) at y = 3.5 covering half of it.
  std::vector<scene::Vertex> tri(3);
  tri[0].position = {5, 3.5f, 5};
  tri[1].position = {5, 3.5f, 6};
  tri[2].position = {6, 3.5f, 5};
  for (scene::Vertex& vertex : tri) vertex.normal = {0, 1, 0};
  b.add_mesh("half", tri, {0, 1, 2}, lamp);
  const scene::Scene scene = b.finish();
  VoxelRun run(scene, kOneMetreVoxels);
  run.render(glm::vec3(4.0f));
  const VoxelVolumes v = run.read();

  const VoxelValue inside = voxel_at(v, {3.5, 3.5, 3.5});
  const VoxelValue quarter = voxel_at(v, {4.5, 3.5, 3.5});
  const VoxelValue half = voxel_at(v, {5.5, 3.5, 5.5});
  std::printf("inside %.3f, quarter %.3f, half triangle %.3f (emission); albedo %.3f %.3f %.3f\n",
              inside.emission.x, quarter.emission.x, half.emission.x, inside.albedo.x,
              quarter.albedo.x, half.albedo.x);
  EXPECT_NEAR(inside.emission.x, 8.0f, 0.01f);
  EXPECT_NEAR(quarter.emission.x, 2.0f, 0.01f);
  EXPECT_NEAR(half.emission.x, 4.0f, 0.01f);
  for (const VoxelValue& voxel : {inside, quarter, half}) {
    EXPECT_NEAR(voxel.albedo.x, 0.6f, 2.0f / 255.0f) << "the albedo is not weighted";
    EXPECT_NEAR(voxel.albedo.a, 1.0f, 1e-3f) << "coverage must not thin the voxel's opacity";
    EXPECT_NEAR(voxel.normal.y, 1.0f, 1e-3f);
  }
}

// The voxels take the base colour as glTF defines it: factor × texture (on the TEXCOORD set and
// through the transform the material names) × vertex colour.
TEST_F(VoxelSurfacesTest, VertexColoursUvSetsAndTextureTransformsReachTheVoxels) {
  scene::SceneBuilder b("attributes");
  scene::Texture halves;  // left half sRGB 188 (linear 0.5), right half white; wide for the mips
  halves.name = "halves";
  halves.width = 64;
  halves.height = 1;
  halves.srgb = true;
  for (uint32_t x = 0; x < halves.width; ++x) {
    const uint8_t value = x < halves.width / 2 ? 188 : 255;
    halves.pixels.insert(halves.pixels.end(), {value, value, value, 255});
  }
  const int texture = b.add_texture(halves);
  scene::Material on_set0 = diffuse({0.8f, 0.8f, 0.8f});
  on_set0.base_color_tex = texture;
  scene::Material on_set1 = on_set0;  // set 1 at u = 0.25, shifted by 0.5: the white half
  on_set1.mappings[0].tex_coord = 1;
  on_set1.mappings[0].offset = glm::vec2(0.5f, 0.0f);
  const int materials[2] = {b.add_material(on_set0), b.add_material(on_set1)};
  for (int i = 0; i < 2; ++i) {
    // Floors facing up at y = 2.5 over x in [2, 4) and [4, 6), z in [2, 6).
    std::vector<scene::Vertex> quad(4);
    const glm::vec3 corners[4] = {{0, 0, 0}, {0, 0, 4}, {2, 0, 4}, {2, 0, 0}};
    for (int k = 0; k < 4; ++k) {
      quad[size_t(k)].position = glm::vec3(2.0f + 2.0f * float(i), 2.5f, 2.0f) + corners[k];
      quad[size_t(k)].normal = {0, 1, 0};
      quad[size_t(k)].uv = {0.25f, 0.5f};
      quad[size_t(k)].uv1 = {0.25f, 0.5f};
      quad[size_t(k)].color = {1.0f, 0.5f, 0.25f, 1.0f};
    }
    b.add_mesh("floor" + std::to_string(i), quad, {0, 1, 2, 0, 2, 3}, materials[i]);
  }
  const scene::Scene scene = b.finish();
  VoxelRun run(scene, kOneMetreVoxels);
  run.render(glm::vec3(4.0f));
  const VoxelVolumes v = run.read();
  const VoxelValue grey = voxel_at(v, {2.5, 2.5, 3.5});
  const VoxelValue white = voxel_at(v, {5.5, 2.5, 3.5});
  std::printf("set 0: albedo %.3f %.3f %.3f; set 1: %.3f %.3f %.3f\n", grey.albedo.x, grey.albedo.y,
              grey.albedo.z, white.albedo.x, white.albedo.y, white.albedo.z);
  const float tolerance = 3.0f / 255.0f;
  EXPECT_NEAR(grey.albedo.x, 0.8f * 0.5029f * 1.0f, tolerance);
  EXPECT_NEAR(grey.albedo.y, 0.8f * 0.5029f * 0.5f, tolerance);
  EXPECT_NEAR(grey.albedo.z, 0.8f * 0.5029f * 0.25f, tolerance);
  EXPECT_NEAR(white.albedo.x, 0.8f * 1.0f, tolerance);
  EXPECT_NEAR(white.albedo.y, 0.8f * 0.5f, tolerance);
  EXPECT_NEAR(white.albedo.z, 0.8f * 0.25f, tolerance);
}

// The faces volume keeps the surfaces of a voxel apart by the way they face, so that injection
// can light each with its own normal (contracts/voxel_volumes.glsl): a floor meeting a wall
// gives two groups weighted by their areas in the voxel, the two faces of a thin slab two
// opposite halves, a plain floor one; each group's plane offset locates its surfaces (rounded
// up by at most a 4-bit step, 1/7 voxel, never behind them).
TEST_F(VoxelSurfacesTest, FacesKeepTheSurfacesOfAVoxelApart) {
  scene::SceneBuilder b("faces");
  const int white = b.add_material(diffuse({0.8f, 0.8f, 0.8f}));
  b.add_quad("floor", {2, 2.5f, 2}, {0, 0, 4}, {4, 0, 0}, white);    // facing +y
  b.add_quad("wall", {2.5f, 2.5f, 2}, {0, 3, 0}, {0, 0, 4}, white);  // facing +x
  b.add_quad("slab_top", {4, 5.51f, 2}, {0, 0, 2}, {2, 0, 0}, white);
  b.add_quad("slab_bottom", {4, 5.49f, 2}, {2, 0, 0}, {0, 0, 2}, white);
  const scene::Scene scene = b.finish();
  VoxelRun run(scene, kOneMetreVoxels);
  run.render(glm::vec3(4.0f));
  const VoxelVolumes v = run.read();
  ASSERT_FALSE(v.faces.empty());
  const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  // Expected groups (index, area share) of the voxel holding `world`; the shares add up to 1.
  auto expect_groups = [&](const char* what, const glm::dvec3& world,
                           const std::vector<std::pair<int, float>>& groups, float offset) {
    const glm::ivec3 w = glm::ivec3(glm::floor(v.window_coord(0, world)));
    const glm::uvec4 texel = v.faces[v.texel(0, w)];
    float total = 0.0f;
    for (int g = 0; g < 6; ++g) {
      const VoxelFace face = decode_voxel_face(texel, g);
      float expected_share = 0.0f;
      for (const auto& [group, share] : groups) {
        if (group == g) expected_share = share;
      }
      const bool expected = expected_share > 0.0f;
      std::printf("%s: group %d share %.3f normal %.3f %.3f %.3f plane offset %.3f\n", what, g,
                  face.share, face.normal.x, face.normal.y, face.normal.z, face.plane_offset);
      if (!expected) {
        EXPECT_EQ(face.share, 0.0f) << what << ", group " << g;
        continue;
      }
      // 5-bit shares: within half a step, and a little for the sampled coverage.
      EXPECT_NEAR(face.share, expected_share, 0.6f / 31.0f) << what << ", group " << g;
      EXPECT_GT(glm::dot(face.normal, axes[g]), 0.9995f) << what << ", group " << g;
      EXPECT_GE(face.plane_offset, offset - 1e-3f) << what << ", group " << g;
      EXPECT_LE(face.plane_offset, offset + 1.0f / 7.0f + 1e-3f) << what << ", group " << g;
      total += face.share;
    }
    EXPECT_NEAR(total, 1.0f, 1.5f / 31.0f) << what;
  };
  expect_groups("floor", {4.5, 2.5, 4.5}, {{2, 1.0f}}, 0.0f);
  // The floor covers the voxel's cross-section (area 1), the wall half of it (0.5).
  expect_groups("floor meeting the wall", {2.5, 2.5, 3.5}, {{0, 1.0f / 3.0f}, {2, 2.0f / 3.0f}},
                0.0f);
  // Each face of the slab lies 0.01 voxel out from the centre along its own normal.
  expect_groups("thin slab", {4.5, 5.5, 2.5}, {{2, 0.5f}, {3, 0.5f}}, 0.01f);
  // An empty voxel has no groups.
  const glm::ivec3 empty = glm::ivec3(glm::floor(v.window_coord(0, {5.5, 4.5, 5.5})));
  EXPECT_EQ(v.faces[v.texel(0, empty)], glm::uvec4(0u));
}

}  // namespace
}  // namespace voxgi::test
