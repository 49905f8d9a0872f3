// Clipmap windows of common.voxelize: the CPU window logic (slabs, nesting, splitting), and on
// the GPU that scrolling the camera (by a few voxels, and by more than a level in one frame)
// leaves volumes equal to a full revoxelization at the new place.

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <set>
#include <tuple>

#include "engine/scene/builtin_scenes.hpp"
#include "engine/scene/scene_builder.hpp"
#include "passes/common/voxel_clipmap_window.hpp"
#include "tests/common/voxel_test_support.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

using passes::common::exposed_slabs;
using passes::common::merge_overlapping;
using passes::common::split_box;
using passes::common::VoxelBox;
using passes::common::window_origin;

TEST(VoxelClipmapWindow, ExposedSlabsAreDisjointAndCoverExactlyTheNewVoxels) {
  const int r = 16;
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> step(-20, 20);
  for (int trial = 0; trial < 200; ++trial) {
    const glm::ivec3 old_origin(step(rng), step(rng), step(rng));
    const glm::ivec3 new_origin = old_origin + glm::ivec3(step(rng), step(rng), step(rng)) / 2;
    std::vector<int> hits(size_t(r) * r * r, 0);
    for (const VoxelBox& b : exposed_slabs(0, old_origin, new_origin, r)) {
      for (int z = b.min.z; z < b.max.z; ++z)
        for (int y = b.min.y; y < b.max.y; ++y)
          for (int x = b.min.x; x < b.max.x; ++x) ++hits[(size_t(z) * r + y) * r + x];
    }
    for (int z = 0; z < r; ++z) {
      for (int y = 0; y < r; ++y) {
        for (int x = 0; x < r; ++x) {
          const glm::ivec3 world = glm::ivec3(x, y, z) + new_origin;
          const glm::ivec3 in_old = world - old_origin;
          const bool was_inside = glm::all(glm::greaterThanEqual(in_old, glm::ivec3(0))) &&
                                  glm::all(glm::lessThan(in_old, glm::ivec3(r)));
          ASSERT_EQ(hits[(size_t(z) * r + y) * r + x], was_inside ? 0 : 1)
              << "voxel " << x << "," << y << "," << z << " trial " << trial;
        }
      }
    }
  }
}

TEST(VoxelClipmapWindow, LevelsStayNestedOnCoarserGrids) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> pos(-1000.0, 1000.0);
  const uint32_t r = 16;
  for (int trial = 0; trial < 500; ++trial) {
    const glm::dvec3 c(pos(rng), pos(rng), pos(rng));
    for (int l = 0; l + 1 < 6; ++l) {
      const double s = 0.1 * std::ldexp(1.0, l);
      const glm::ivec3 fine = window_origin(c, s, r), coarse = window_origin(c, 2 * s, r);
      // The fine window's corner lies on the coarse grid and inside the coarse window.
      EXPECT_EQ(fine.x % 2, 0);
      const glm::ivec3 fine_in_coarse = fine / 2;
      EXPECT_TRUE(glm::all(glm::greaterThanEqual(fine_in_coarse, coarse)));
      EXPECT_TRUE(glm::all(glm::lessThanEqual(fine_in_coarse + int(r / 2), coarse + int(r))));
    }
  }
}

// A random box scene away from the origin and a camera in or around it: the camera lies in
// the box's bounds grown by `around` times its largest side on every side.
struct RandomBoxAndCamera {
  glm::dvec3 min, max, side;
  double extent = 0.0;
  glm::dvec3 camera;
};
RandomBoxAndCamera random_box_and_camera(std::mt19937& rng, double around) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  RandomBoxAndCamera s;
  s.min = glm::dvec3(unit(rng) * 10.0 - 5.0, unit(rng) * 10.0 - 5.0, unit(rng) - 0.5);
  s.side = glm::dvec3(0.1 + unit(rng), 0.1 + unit(rng), 0.1 + unit(rng));
  s.max = s.min + s.side;
  s.extent = std::max({s.side.x, s.side.y, s.side.z});
  s.camera = s.min +
             glm::dvec3(unit(rng), unit(rng), unit(rng)) * ((1.0 + 2.0 * around) * s.extent) -
             around * s.extent;
  return s;
}

// Windows that follow the camera, of the automatic voxel size, hold the whole scene with the
// one-voxel margin of the consumers wherever the camera is (here up to five scene sizes
// outside): they centre on the camera clamped into the scene bounds.
TEST(VoxelClipmapWindow, AutomaticSizeHoldsTheSceneFromAnyCamera) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 300; ++trial) {
    const RandomBoxAndCamera scene = random_box_and_camera(rng, 5.0);
    const glm::dvec3 &scene_min = scene.min, &scene_max = scene.max, &camera = scene.camera;
    const double extent = scene.extent;
    const glm::dvec3 center = passes::common::window_center_in_scene(camera, scene_min, scene_max);
    for (uint32_t r : {16u, 32u, 128u}) {
      for (uint32_t levels : {1u, 3u, 6u}) {
        const double reach = passes::common::window_reach(center, scene_min, scene_max);
        const double coarsest = passes::common::auto_voxel_size(extent, r, levels, reach) *
                                std::ldexp(1.0, int(levels) - 1);
        const glm::dvec3 anchor =
            passes::common::snap_anchor(0.5 * (scene_min + scene_max), coarsest);
        const glm::ivec3 origin = window_origin(center - anchor, coarsest, r);
        const glm::dvec3 lo = (scene_min - anchor) / coarsest - glm::dvec3(origin);
        const glm::dvec3 hi = (scene_max - anchor) / coarsest - glm::dvec3(origin);
        for (int a = 0; a < 3; ++a) {
          ASSERT_GE(lo[a], 1.0) << "trial " << trial << " R " << r << " L " << levels;
          ASSERT_LE(hi[a], double(r) - 1.0) << "trial " << trial << " R " << r << " L " << levels;
        }
      }
    }
  }
}

// Centring on the camera clamped into the scene bounds loses nothing: every scene point within
// a level's half-width of the camera is within it of the clamped centre, and a camera outside
// the scene brings scene points into the finer levels.
TEST(VoxelClipmapWindow, ClampedCentreHoldsEveryScenePointTheCameraWindowHeld) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const glm::dvec3 scene_min(-1.0, 0.0, 2.0), scene_max(3.0, 1.5, 2.5);
  int gained = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const glm::dvec3 camera = glm::dvec3(unit(rng), unit(rng), unit(rng)) * 12.0 - 4.0;
    const glm::dvec3 center = passes::common::window_center_in_scene(camera, scene_min, scene_max);
    const glm::dvec3 point =
        glm::mix(scene_min, scene_max, glm::dvec3(unit(rng), unit(rng), unit(rng)));
    const auto chebyshev = [](const glm::dvec3& d) {
      return std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    };
    const double from_camera = chebyshev(point - camera);
    const double from_center = chebyshev(point - center);
    ASSERT_LE(from_center, from_camera + 1e-12) << "trial " << trial;
    if (from_center < 0.5 * from_camera) ++gained;
  }
  EXPECT_GT(gained, 100);
  // Inside the bounds the camera itself is the centre; empty bounds leave the camera.
  EXPECT_EQ(passes::common::window_center_in_scene({0.5, 1.0, 2.2}, scene_min, scene_max),
            glm::dvec3(0.5, 1.0, 2.2));
  EXPECT_EQ(passes::common::window_center_in_scene({7.0, 1.0, 2.2}, glm::dvec3(INFINITY),
                                                   glm::dvec3(-INFINITY)),
            glm::dvec3(7.0, 1.0, 2.2));
}

// Windows that follow the camera, placed as common.voxelize places them: each level centred on
// the camera clamped into the scene, moved into the bounds as far as its width allows
// (level_window_center), then nested (nest_window_origins). Each level holds, per axis, as much
// of the scene as a window of its width can (up to the snapping and nesting, a few voxels),
// never less than the window centred on the clamped camera, and often much more; the levels
// stay nested with the margin; a level as wide as the scene holds all of it.
TEST(VoxelClipmapWindow, LevelWindowsHoldAsMuchOfTheSceneAsTheirWidthAllows) {
  std::mt19937 rng(7);
  int gained = 0, whole = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const RandomBoxAndCamera scene = random_box_and_camera(rng, 2.0);
    const glm::dvec3 &scene_min = scene.min, &scene_max = scene.max, &side = scene.side;
    const double extent = scene.extent;
    const glm::dvec3 center =
        passes::common::window_center_in_scene(scene.camera, scene_min, scene_max);
    for (uint32_t r : {8u, 16u, 64u}) {
      for (uint32_t levels : {2u, 4u, 6u}) {
        const double reach = passes::common::window_reach(center, scene_min, scene_max);
        const double finest = passes::common::auto_voxel_size(extent, r, levels, reach);
        const glm::dvec3 anchor = passes::common::snap_anchor(
            0.5 * (scene_min + scene_max), finest * std::ldexp(1.0, int(levels) - 1));
        std::vector<glm::ivec3> origins(levels), common(levels);
        for (uint32_t l = 0; l < levels; ++l) {
          const double size = finest * std::ldexp(1.0, int(l));
          const glm::dvec3 c = passes::common::level_window_center(center, scene_min, scene_max,
                                                                   0.5 * double(r) * size);
          origins[l] = window_origin(c - anchor, size, r);
          common[l] = window_origin(center - anchor, size, r);
        }
        passes::common::nest_window_origins(origins, r, 4);
        const int margin = std::min(4, int(r) / 4);
        for (uint32_t l = 0; l < levels; ++l) {
          const double size = finest * std::ldexp(1.0, int(l));
          if (l + 1 < levels) {
            const glm::ivec3 lo = origins[l + 1] * 2 + glm::ivec3(margin);
            const glm::ivec3 hi = (origins[l + 1] + glm::ivec3(int(r))) * 2 - glm::ivec3(margin);
            ASSERT_TRUE(glm::all(glm::greaterThanEqual(origins[l], lo)) &&
                        glm::all(glm::lessThanEqual(origins[l] + glm::ivec3(int(r)), hi)))
                << "trial " << trial << " R " << r << " level " << l;
          }
          bool holds_all = true;
          for (int a = 0; a < 3; ++a) {
            const auto overlap = [&](const glm::ivec3& origin) {
              const double lo = anchor[a] + origin[a] * size;
              return std::max(0.0,
                              std::min(lo + r * size, scene_max[a]) - std::max(lo, scene_min[a]));
            };
            const double best = std::min(double(r) * size, side[a]);
            ASSERT_GE(overlap(origins[l]), best - 8.0 * size)
                << "trial " << trial << " R " << r << " level " << l << " axis " << a;
            ASSERT_GE(overlap(origins[l]), overlap(common[l]) - 8.0 * size)
                << "trial " << trial << " R " << r << " level " << l << " axis " << a;
            if (overlap(origins[l]) > overlap(common[l]) + 4.0 * size) ++gained;
            holds_all = holds_all && overlap(origins[l]) >= side[a] - 1e-9 * extent;
          }
          if (double(r) * size >= extent + 8.0 * size) {
            EXPECT_TRUE(holds_all) << "trial " << trial << " R " << r << " level " << l;
            ++whole;
          }
        }
      }
    }
  }
  EXPECT_GT(gained, 5000);
  EXPECT_GT(whole, 1500);
  // A camera in front of a box: the level as wide as the box holds all of it.
  const glm::dvec3 box_min(0.0), box_max(0.556, 0.549, 0.559);
  const glm::dvec3 c =
      passes::common::window_center_in_scene({0.278, 0.273, -0.8}, box_min, box_max);
  EXPECT_EQ(passes::common::level_window_center(c, box_min, box_max, 0.3),
            0.5 * (box_min + box_max));
  const glm::dvec3 near = passes::common::level_window_center(c, box_min, box_max, 0.1);
  EXPECT_NEAR(near.z, 0.1, 1e-12);  // as far in as its half-width allows, not beyond the front
  EXPECT_EQ(
      passes::common::level_window_center(c, glm::dvec3(INFINITY), glm::dvec3(-INFINITY), 0.1), c);
}

// Windows that stay put start at a multiple of R with the fixed-window anchor, so their storage
// is the identity, and lie exactly where the plain anchor put them: the voxel grid is the same.
TEST(VoxelClipmapWindow, FixedWindowsStartOnTheTextureGridWhereTheyLayBefore) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int aligned = 0, trials = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const glm::dvec3 center = glm::dvec3(unit(rng), unit(rng), unit(rng)) * 2000.0 - 1000.0;
    const double coarsest = 0.001 + unit(rng);
    for (uint32_t r : {8u, 32u, 128u}) {
      for (uint32_t levels : {1u, 4u}) {
        ++trials;
        const glm::dvec3 plain = passes::common::snap_anchor(center, coarsest);
        const glm::dvec3 fixed = passes::common::fixed_window_anchor(center, coarsest, r);
        const glm::ivec3 coarse = window_origin(center - fixed, coarsest, r);
        if (glm::all(glm::equal(coarse, glm::ivec3(0)))) ++aligned;
        for (uint32_t l = 0; l < levels; ++l) {
          const double size = coarsest / std::ldexp(1.0, int(levels - 1 - l));
          const glm::dvec3 before =
              plain + glm::dvec3(window_origin(center - plain, size, r)) * size;
          const glm::dvec3 after =
              fixed + glm::dvec3(window_origin(center - fixed, size, r)) * size;
          for (int a = 0; a < 3; ++a) {
            ASSERT_NEAR(after[a], before[a], 1e-9 * (1.0 + std::abs(before[a])))
                << "trial " << trial << " R " << r << " level " << l;
          }
          // The anchor stays on every level's grid of window corners (even voxel counts).
          const double steps = (plain[0] - fixed[0]) / size;
          ASSERT_NEAR(std::remainder(steps, 2.0), 0.0, 1e-6) << "trial " << trial;
        }
      }
    }
  }
  // Only a centre exactly halfway between two anchor cells can round the other way.
  EXPECT_EQ(aligned, trials);
}

TEST(VoxelClipmapWindow, SplitAndMergeKeepEveryVoxel) {
  const VoxelBox box{2, {1, 2, 3}, {14, 9, 16}};
  for (int64_t budget : {7, 13, 91, 1000, 100000}) {
    int64_t total = 0;
    for (const VoxelBox& piece : split_box(box, budget)) {
      EXPECT_LE(piece.voxels(), std::max<int64_t>(budget, box.max.x - box.min.x));
      EXPECT_EQ(piece.level, 2);
      total += piece.voxels();
    }
    EXPECT_EQ(total, box.voxels()) << budget;
  }
  const std::vector<VoxelBox> merged = merge_overlapping({{0, {0, 0, 0}, {4, 4, 4}},
                                                          {0, {3, 3, 3}, {6, 6, 6}},
                                                          {1, {0, 0, 0}, {2, 2, 2}},
                                                          {0, {10, 10, 10}, {12, 12, 12}},
                                                          {0, {5, 5, 5}, {5, 9, 9}}});
  EXPECT_EQ(merged.size(), 3u);  // the empty box is dropped, the overlapping pair merged
}

// Boxes and triangles spread over 40 m.
scene::Scene spread_scene() {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  scene::SceneBuilder b("spread");
  for (int i = 0; i < 24; ++i) {
    scene::Material m = diffuse({unit(rng), unit(rng), unit(rng)});
    if (i % 5 == 0) m.emissive = glm::vec3(unit(rng), unit(rng), unit(rng)) * 20.0f;
    const int mat = b.add_material(m);
    const glm::vec3 center = (glm::vec3(unit(rng), unit(rng), unit(rng)) - 0.5f) * 40.0f;
    const glm::vec3 size = glm::vec3(0.3f) + glm::vec3(unit(rng), unit(rng), unit(rng)) * 3.0f;
    b.add_box("box" + std::to_string(i), center, size, mat, unit(rng) * 3.0f);
  }
  const int mat = b.add_material(diffuse({0.9f, 0.9f, 0.9f}));
  const scene::Primitive triangles = random_scene(3, glm::mat4(1.0f)).meshes[0].primitives[0];
  b.add_mesh("tris", triangles.vertices, triangles.indices, mat,
             glm::scale(glm::mat4(1.0f), glm::vec3(6.0f)));
  return b.finish();
}

struct Mismatch {
  size_t voxels = 0, occupied = 0, different = 0;
};

// Compares two runs' volumes level by level through each one's toroidal mapping.
Mismatch compare_volumes(const VoxelVolumes& a, const VoxelVolumes& b) {
  Mismatch m;
  const int r = static_cast<int>(a.resolution);
  for (int l = 0; l < int(a.levels); ++l) {
    EXPECT_EQ(glm::ivec4(a.info.levels[l].origin_voxel), glm::ivec4(b.info.levels[l].origin_voxel))
        << "level " << l;
    for (int z = 0; z < r; ++z) {
      for (int y = 0; y < r; ++y) {
        for (int x = 0; x < r; ++x) {
          const size_t ta = a.texel(l, {x, y, z}), tb = b.texel(l, {x, y, z});
          ++m.voxels;
          m.occupied += a.normal[ta].w > 0.5f;
          const bool same =
              std::memcmp(&a.albedo_bytes[ta * 4], &b.albedo_bytes[tb * 4], 4) == 0 &&
              std::memcmp(&a.normal_bytes[ta * 8], &b.normal_bytes[tb * 8], 8) == 0 &&
              std::memcmp(&a.emission_bytes[ta * 8], &b.emission_bytes[tb * 8], 8) == 0;
          m.different += !same;
        }
      }
    }
  }
  return m;
}

const std::map<std::string, std::string> kClipmapParams = {{"voxel.resolution", "16"},
                                                           {"voxel.levels", "3"},
                                                           {"voxelize.voxel_size", "0.25"},
                                                           {"voxelize.center", "camera"}};

class VoxelScrollTest : public GpuTest, public ::testing::WithParamInterface<const char*> {};

// The scratch buffer holding a whole level, and a fifth of one (levels split into pieces).
INSTANTIATE_TEST_SUITE_P(ScratchSize, VoxelScrollTest, ::testing::Values("1", "5"));

TEST_P(VoxelScrollTest, ScrollingEqualsFullRevoxelization) {
  const scene::Scene scene = spread_scene();
  std::map<std::string, std::string> params = kClipmapParams;
  params["voxel.scratch_divisor"] = GetParam();
  VoxelRun moving(scene, params);
  // Level widths: 4, 8 and 16 m. Steps: a few voxels, sub-voxel, then 17 m (more than the
  // coarsest level) in one frame, then back by a few voxels on every axis.
  const std::vector<glm::vec3> path = {{0.0f, 0.0f, 0.0f},   {1.3f, -0.6f, 0.9f},
                                       {1.35f, -0.6f, 0.9f}, {2.9f, 0.4f, -0.7f},
                                       {19.9f, 0.4f, -0.7f}, {18.1f, 1.7f, 1.2f}};
  for (size_t i = 0; i < path.size(); ++i) {
    moving.render(path[i]);
    const std::string skipped = moving.last_skip_reason();
    const double moving_ms = moving.last_gpu_ms();
    VoxelRun fresh(scene, kClipmapParams);
    fresh.render(path[i]);
    const Mismatch m = compare_volumes(moving.read(), fresh.read());
    std::printf(
        "[scroll %zu] camera (%.2f %.2f %.2f): %zu occupied of %zu, %zu differ; "
        "incremental %.2f ms%s, full %.2f ms\n",
        i, path[i].x, path[i].y, path[i].z, m.occupied, m.voxels, m.different, moving_ms,
        skipped.empty() ? "" : (" (skipped: " + skipped + ")").c_str(), fresh.last_gpu_ms());
    EXPECT_GT(m.occupied, 0u) << "step " << i;
    EXPECT_EQ(m.different, 0u) << "step " << i;
    if (i == 2) {
      EXPECT_EQ(skipped, "static voxels up to date, window unchanged")
          << "a move below the window snapping must not revoxelize";
    }
  }
}

class VoxelWindowPlacementTest : public GpuTest {};

// common.voxelize itself places the windows (not a copy of its arithmetic): the built-in Cornell
// box seen from its camera 0.8 m in front, a 6-level 64³ clipmap. Every level as wide as the box
// holds all of it (level 4 has the voxel of one dense 64³ level fitted to the box), the finer
// ones hold as much of it as their width allows, and each level lies inside the next coarser
// one with four of its voxels to spare.
TEST_F(VoxelWindowPlacementTest, ACameraOutsideTheCornellBoxGetsItWholeInTheLevelAsWideAsIt) {
  const scene::Scene scene = scene::make_builtin_scene("cornell");
  glm::vec3 lo, hi;
  scene.bounds(lo, hi);
  const glm::dvec3 box_min(lo), box_max(hi), side = box_max - box_min;
  const double extent = std::max({side.x, side.y, side.z});
  VoxelRun run(scene, {{"voxel.resolution", "64"}, {"voxel.levels", "6"}});
  run.render({0.278f, 0.273f, -0.8f});
  const VoxelVolumes v = run.read();
  const int r = int(v.resolution);
  int whole = 0;
  for (int l = 0; l < int(v.levels); ++l) {
    const double size = v.info.levels[l].min_corner_size.w;
    const glm::dvec3 window_min =
        glm::dvec3(v.info.anchor) + glm::dvec3(glm::vec3(v.info.levels[l].min_corner_size));
    for (int a = 0; a < 3; ++a) {
      const double overlap =
          std::min(window_min[a] + r * size, box_max[a]) - std::max(window_min[a], box_min[a]);
      EXPECT_GE(overlap, std::min(r * size, side[a]) - 8.0 * size)
          << "level " << l << " axis " << a;
    }
    // A level as wide as the box with room for the snapping (a voxel) each side holds all of it.
    if (r * size >= extent + 2.0 * size) {
      ++whole;
      for (int a = 0; a < 3; ++a) {
        EXPECT_LE(window_min[a], box_min[a]) << "level " << l << " axis " << a;
        EXPECT_GE(window_min[a] + r * size, box_max[a]) << "level " << l << " axis " << a;
      }
    }
    if (l + 1 < int(v.levels)) {
      const glm::ivec3 fine = glm::ivec3(v.info.levels[l].origin_voxel);
      const glm::ivec3 coarse = glm::ivec3(v.info.levels[l + 1].origin_voxel);
      EXPECT_TRUE(glm::all(glm::greaterThanEqual(fine, coarse * 2 + glm::ivec3(4))) &&
                  glm::all(glm::lessThanEqual(fine + glm::ivec3(r),
                                              (coarse + glm::ivec3(r)) * 2 - glm::ivec3(4))))
          << "level " << l;
    }
  }
  // Levels 4 and 5 (level 4: 64 voxels of 0.0093 m over a 0.559 m box).
  EXPECT_EQ(whole, 2);
  EXPECT_NEAR(v.info.levels[4].min_corner_size.w, extent / 60.0, 1e-3 * extent);
}

}  // namespace
}  // namespace voxgi::test
