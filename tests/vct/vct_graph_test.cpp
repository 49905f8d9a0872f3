// graphs/vct.json on scenes: the white furnace (energy), light leaking through a one-voxel
// wall, colour bleeding in the Cornell box, frame-to-frame stability, skipping of injection
// and filtering on static frames, half-resolution tracing against full resolution.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "engine/scene/scene_builder.hpp"
#include "tests/common/render_harness.hpp"
#include "tests/gpu/gpu_test_env.hpp"
#include "tests/vct/vct_scenes.hpp"

namespace voxgi::test {
namespace {

class VctGraphTest : public GpuTest {};

// graphs/vct.json pinned to one dense 64^3 level: the scenes here are closed boxes sized for it,
// and a small volume keeps the tests fast on a CPU device.
RenderSetup dense_vct_setup() {
  RenderSetup setup;
  setup.graph = "graphs/vct.json";
  setup.overrides = {{"voxel.resolution", "64"}, {"voxel.levels", "1"}};
  return setup;
}

RenderSetup vct_setup(scene::Scene scene, uint32_t size = 64) {
  RenderSetup setup = dense_vct_setup();
  setup.scene_data = std::move(scene);
  setup.width = size;
  setup.height = size;
  return setup;
}

// The pixel of `image` (rendered by `harness`) that world point `p` projects to, clamped into
// the image.
glm::ivec2 pixel_of(const RenderHarness& harness, const RenderedImage& image, glm::vec3 p) {
  const glm::vec4 clip = harness.view_proj() * glm::vec4(p, 1.0f);
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  return {glm::clamp(int((ndc.x * 0.5f + 0.5f) * float(image.width)), 0, int(image.width) - 1),
          glm::clamp(int((ndc.y * 0.5f + 0.5f) * float(image.height)), 0, int(image.height) - 1)};
}

// Mean of the rgb channels over pixels where `mask` holds.
glm::vec3 mean_rgb(const RenderedImage& image) {
  glm::dvec3 sum(0.0);
  for (uint32_t y = 0; y < image.height; ++y) {
    for (uint32_t x = 0; x < image.width; ++x) sum += glm::dvec3(glm::vec3(image.at(x, y)));
  }
  return glm::vec3(sum / double(image.width * image.height));
}

// White furnace: a closed box of albedo 1 whose walls emit Le, no lights. Every diffuse cone
// sees Le, so E = pi Le and the indirect diffuse c_diff/pi E equals Le exactly. The voxelized
// walls are a few voxels thick so cones cannot leave the box. Measured 2.8% low at 64^2, worst
// pixel 61% (2.9% and 63% at 128^2; it was 1.9% and 22% when cones gathered their own surface,
// which in a furnace happens to shine exactly Le, and leaked through thin walls, docs/vct.md;
// 0.36% after those fixes, 3.9% once voxels sent light only where their surfaces face, 5.5%
// once the filter did so too).
// What is left is a cone's footprint at coarse levels of detail taking in surfaces it travels
// away from (a cone rising from a wall near the floor blends in the floor's voxels): their
// opacity comes with none of their light now that a floor's top no longer shines upwards,
// where their light used to be exactly Le here (docs/error-budget.md, tenth round). Tolerance
// 6%; the indirect light must never exceed Le.
TEST_F(VctGraphTest, WhiteFurnaceIndirectEqualsEmission) {
  const float le = 0.5f;
  RenderHarness harness(vct_setup(furnace_box(le)));
  harness.render();
  const RenderedImage indirect = harness.output("indirect");
  expect_finite_non_negative(indirect, "indirect");
  const glm::vec3 mean = mean_rgb(indirect);
  float worst_pixel = 0.0f;
  for (uint32_t y = 0; y < indirect.height; ++y) {
    for (uint32_t x = 0; x < indirect.width; ++x) {
      worst_pixel = std::max(worst_pixel, std::abs(indirect.at(x, y).g / le - 1.0f));
    }
  }
  const float error = std::abs(mean.g / le - 1.0f);
  std::printf(
      "white furnace (64^3, 1 level, 64^2): mean indirect / Le = %.4f %.4f %.4f, "
      "error %.2f%%, worst pixel %.2f%%\n",
      mean.r / le, mean.g / le, mean.b / le, 100.0f * error, 100.0f * worst_pixel);
  EXPECT_LT(error, 0.06f);
  EXPECT_LE(mean.g, le * 1.001f) << "the gather creates energy";
}

// The furnace with a white metal floor (f0 = 1): the floor reflects only through the
// specular cone, which sees Le and weighs it by the lobe's directional albedo (0.89 at
// roughness 0.2: single-scattering GGX loses the rest, in the path tracer too); the walls
// reflect Le. The metal makes the scene glossy, so the specular pass also adds S Le on the
// white dielectric walls, whose diffuse must then reflect only (1 - S) of what arrives
// (vct.cone_trace's specular_layer): without that the image read 1.0139 Le, the walls
// 1.035-1.05 (docs/error-budget.md, thirty-ninth round). Now 0.969. The same 5% tolerance,
// and never more than Le.
TEST_F(VctGraphTest, WhiteFurnaceWithAMetalFloorKeepsLe) {
  const float le = 0.5f;
  RenderSetup setup = vct_setup(furnace_box(le, true));
  RenderHarness harness(setup);
  ASSERT_NE(harness.compiled().find_pass("cone_trace_specular"), nullptr)
      << "the metal floor makes the scene glossy";
  harness.render();
  const RenderedImage indirect = harness.output("indirect");
  expect_finite_non_negative(indirect, "indirect");
  const float mean = mean_rgb(indirect).g;
  const float error = std::abs(mean / le - 1.0f);
  std::printf("white furnace with a metal floor: mean indirect / Le = %.4f, error %.2f%%\n",
              mean / le, 100.0f * error);
  EXPECT_LT(error, 0.05f);
  EXPECT_LE(mean, le * 1.001f) << "diffuse and specular together create energy";
}

// Both furnaces in vct.filter's front-light mode (graphs/vct_front_light.json), whose cones read
// the light over the facing shares: every surface shows Le from the front, so the division must
// return Le, and neither furnace more (measured 0.968 and, with the metal floor, 0.965; 1.0102
// before the diffuse gave the specular its share).
TEST_F(VctGraphTest, FrontLightWhiteFurnacesKeepLe) {
  const float le = 0.5f;
  for (bool metal_floor : {false, true}) {
    RenderSetup setup = vct_setup(furnace_box(le, metal_floor));
    setup.graph = "graphs/vct_front_light.json";
    RenderHarness harness(setup);
    ASSERT_EQ(harness.compiled().find_pass("cone_trace_specular") != nullptr, metal_floor);
    harness.render();
    const RenderedImage indirect = harness.output("indirect");
    expect_finite_non_negative(indirect, "indirect");
    const glm::vec3 mean = mean_rgb(indirect);
    std::printf("front light, white furnace%s: mean indirect / Le = %.4f\n",
                metal_floor ? " with a metal floor" : "", mean.g / le);
    EXPECT_LT(std::abs(mean.g / le - 1.0f), metal_floor ? 0.05f : 0.06f);
    EXPECT_LE(mean.g, le * 1.001f) << "the gather creates energy";
  }
}

// Two rooms with a partition one voxel thick; the light is in room 1 only (its shadow map
// keeps direct light out of room 2). Whatever indirect light room 2 receives leaked through
// the partition's voxels (a voxel holds both faces, so its radiance is seen from both sides)
// or through coarse mips. Bound: room 2 gets less than 10% of room 1's mean indirect.
TEST_F(VctGraphTest, OneVoxelWallLeaksLittle) {
  double means[2];
  double shadow[2];
  for (int room = 0; room < 2; ++room) {
    RenderSetup setup = vct_setup(two_rooms(room), 64);
    setup.overrides["voxelize.voxel_size"] = std::to_string(kTwoRoomsVoxel);
    RenderHarness harness(setup);
    harness.render();
    const RenderedImage indirect = harness.output("indirect");
    expect_finite_non_negative(indirect, "indirect");
    const glm::vec3 m = mean_rgb(indirect);
    means[room] = (m.r + m.g + m.b) / 3.0;
    const RenderedImage visibility = harness.output("shadow");
    expect_finite_non_negative(visibility, "shadow");
    shadow[room] = mean_rgb(visibility).r;
  }
  // The soft-shadow cone towards the light: room 1 sees the light, room 2 is behind the wall.
  // A one-voxel wall is thin for a cone (trilinear blending with the empty neighbours leaves
  // it partly transparent), so room 2 keeps some visibility: measured 0.14, bound 0.25.
  std::printf("soft-shadow cone visibility of the light: room 1 %.3f, room 2 %.3f\n", shadow[0],
              shadow[1]);
  EXPECT_GT(shadow[0], 0.6);
  EXPECT_LT(shadow[1], 0.25);
  const double leak = means[1] / std::max(means[0], 1e-12);
  std::printf("leak through a one-voxel wall: mean indirect room 2 / room 1 = %.4f (%.3g / %.3g)\n",
              leak, means[1], means[0]);
  EXPECT_GT(means[0], 0.0);
  EXPECT_LT(leak, 0.10);
}

// Cornell box: light bounced off the red wall reaches the ceiling next to it, so the
// ceiling is redder (higher R/G) near the red wall than near the green one, and the other
// way round for green; outputs are finite; a static scene gives bit-identical frames.
TEST_F(VctGraphTest, CornellBleedsTheRightColourAndIsStable) {
  RenderSetup setup = dense_vct_setup();
  setup.scene = "cornell";
  setup.width = setup.height = 64;  // two frames: 128^2 took 70 s on lavapipe
  RenderHarness harness(setup);
  harness.render();
  const RenderedImage indirect = harness.output("indirect");
  const RenderedImage linear = harness.output("linear");
  expect_finite_non_negative(indirect, "indirect");
  expect_finite_non_negative(linear, "linear");
  expect_finite_non_negative(harness.output("ao"), "ao");

  // The builtin box: red wall at x = 0.556, green wall at x = 0, ceiling at y = 0.5488.
  auto ceiling_colour = [&](float x) {
    const glm::ivec2 centre = pixel_of(harness, indirect, {x, 0.5480f, 0.30f});
    const int px = centre.x, py = centre.y;
    glm::vec3 sum(0.0f);
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int sx = glm::clamp(px + dx, 0, int(indirect.width) - 1);
        const int sy = glm::clamp(py + dy, 0, int(indirect.height) - 1);
        sum += glm::vec3(indirect.at(uint32_t(sx), uint32_t(sy)));
      }
    }
    return sum / 9.0f;
  };
  const glm::vec3 near_red = ceiling_colour(0.50f);
  const glm::vec3 near_green = ceiling_colour(0.056f);
  std::printf("ceiling indirect near red wall %.4f %.4f %.4f, near green wall %.4f %.4f %.4f\n",
              near_red.r, near_red.g, near_red.b, near_green.r, near_green.g, near_green.b);
  ASSERT_GT(near_red.g, 0.0f);
  ASSERT_GT(near_green.g, 0.0f);
  EXPECT_GT(near_red.r / near_red.g, near_green.r / near_green.g);
  EXPECT_GT(near_green.g / near_green.r, near_red.g / near_red.r);

  harness.render();
  const RenderedImage second = harness.output("linear");
  ASSERT_EQ(second.rgba.size(), linear.rgba.size());
  EXPECT_EQ(std::memcmp(second.rgba.data(), linear.rgba.data(), linear.rgba.size() * 4), 0)
      << "a static frame differs from the previous one";
  // The second frame reuses the radiance volumes.
  for (const auto& t : harness.executor().timings()) {
    if (t.pass == "inject" || t.pass == "filter") {
      EXPECT_FALSE(t.skipped.empty()) << t.pass << " ran on a static frame";
    }
    if (t.pass == "cone_trace") {
      EXPECT_TRUE(t.skipped.empty());
    }
  }
}

// A static frame (the third of a static scene) records no barrier on what the skipped passes
// write: shadow maps, voxel volumes, radiance and the filtered volumes stay as the first frame
// left them, which the validation layers (synchronisation included) check.
TEST_F(VctGraphTest, StaticFrameRecordsNoBarrierOnTheVoxelVolumes) {
  RenderSetup setup = dense_vct_setup();
  setup.scene = "cornell";
  setup.width = setup.height = 32;  // three frames; the barriers do not depend on the size
  RenderHarness harness(setup);
  graph::Executor& executor = harness.executor();
  harness.render();
  const size_t first = graph::barrier_count(executor.frame_barriers());
  const RenderedImage first_image = harness.output("linear");
  harness.render(2);
  for (const auto& t : executor.timings()) {
    const bool may_skip =
        t.pass == "shadows" || t.pass == "voxelize" || t.pass == "inject" || t.pass == "filter";
    EXPECT_EQ(t.skipped.empty(), !may_skip) << t.pass << ": " << t.skipped;
  }
  const graph::CompiledGraph& g = executor.compiled();
  const graph::FrameBarriers& frame = executor.frame_barriers();
  std::vector<std::string> touched;
  auto scan = [&](const std::vector<graph::Barrier>& list) {
    for (const graph::Barrier& b : list) {
      touched.push_back(g.resources[static_cast<size_t>(b.resource)].info.name);
    }
  };
  scan(frame.frame_start);
  for (const std::vector<graph::Barrier>& pass : frame.passes) scan(pass);
  scan(frame.frame_end);
  for (const std::string& name : touched) {
    EXPECT_NE(name.rfind("voxel.", 0), 0u) << name;
    EXPECT_NE(name.rfind("vct.", 0), 0u) << name;
    EXPECT_NE(name.rfind("shadow.", 0), 0u) << name;
  }
  std::printf("graph barriers: %zu in the first frame, %zu in a static frame\n", first,
              touched.size());
  EXPECT_LT(touched.size(), first);
  const RenderedImage still = harness.output("linear");
  ASSERT_EQ(still.rgba.size(), first_image.rgba.size());
  EXPECT_EQ(std::memcmp(still.rgba.data(), first_image.rgba.data(), first_image.rgba.size() * 4), 0)
      << "a static frame differs from the first";
}

// The interleaved gather averages each pixel's n x n window over its own plane, and half
// resolution upsamples; both must blend the light (E / pi), never the reflected result, or a
// surface's albedo bleeds into its neighbours': the built-in box's emitter has a black base
// colour on the ceiling's plane (1 mm under it), so its indirect light is exactly 0 however
// bright the ceiling beside it is, as in the path tracer.
void expect_black_emitter_reflects_nothing(const RenderHarness& harness,
                                           const RenderedImage& indirect, const char* what) {
  // The inner part of the light quad (x 0.213-0.343, z 0.227-0.332 at y = 0.548).
  float emitter_max = 0.0f;
  for (float x = 0.233f; x <= 0.323f; x += 0.01f) {
    for (float z = 0.247f; z <= 0.312f; z += 0.005f) {
      const glm::ivec2 p = pixel_of(harness, indirect, {x, 0.548f, z});
      const glm::vec4 v = indirect.at(uint32_t(p.x), uint32_t(p.y));
      emitter_max = std::max({emitter_max, v.r, v.g, v.b});
    }
  }
  const glm::ivec2 beside = pixel_of(harness, indirect, {0.16f, 0.5488f, 0.28f});
  const float ceiling = indirect.at(uint32_t(beside.x), uint32_t(beside.y)).g;
  std::printf("[%s] emitter: max indirect %.5f; ceiling beside it %.4f\n", what, emitter_max,
              ceiling);
  EXPECT_GT(ceiling, 0.02f) << what;
  EXPECT_EQ(emitter_max, 0.0f) << what
                               << ": the emitter's black albedo takes its neighbours' light";
}

// Half resolution with depth- and normal-aware upsampling stays close to full resolution:
// mean absolute difference under 15% of the mean (measured 11% at 96^2, where contact
// shadows and silhouettes are a few pixels wide); at both, the black emitter reflects nothing.
TEST_F(VctGraphTest, HalfResolutionMatchesFullResolution) {
  RenderSetup full = dense_vct_setup();
  full.scene = "cornell";
  full.width = full.height = 96;
  RenderSetup half = full;
  half.overrides["cone_trace.resolution"] = "half";
  RenderHarness full_harness(full);
  full_harness.render();
  RenderHarness half_harness(half);
  half_harness.render();
  const RenderedImage a = full_harness.output("indirect");
  const RenderedImage b = half_harness.output("indirect");
  expect_finite_non_negative(b, "half-resolution indirect");
  expect_black_emitter_reflects_nothing(full_harness, a, "full resolution");
  expect_black_emitter_reflects_nothing(half_harness, b, "half resolution");
  double diff = 0.0, total = 0.0;
  for (size_t i = 0; i < a.rgba.size(); i += 4) {
    for (int c = 0; c < 3; ++c) {
      diff += std::abs(double(a.rgba[i + c]) - double(b.rgba[i + c]));
      total += std::abs(double(a.rgba[i + c]));
    }
  }
  const double relative = diff / std::max(total, 1e-12);
  std::printf("half vs full resolution: mean |difference| / mean = %.4f\n", relative);
  EXPECT_LT(relative, 0.15);
}

// The built-in Cornell box's back wall above the tall block and under the ceiling (z = 0.5592),
// a plane of smooth light, in the indirect image of the dense vct graph at 128 x 128.
struct BackWallIndirect {
  RenderedImage indirect;
  glm::ivec2 lo, hi;  // the region's pixel bounds
  double luminance(int x, int y) const {
    const glm::vec4 v = indirect.at(uint32_t(x), uint32_t(y));
    return 0.2126 * v.r + 0.7152 * v.g + 0.0722 * v.b;
  }
};

BackWallIndirect render_back_wall_indirect() {
  RenderSetup setup = dense_vct_setup();
  setup.scene = "cornell";
  setup.width = setup.height = 128;
  RenderHarness harness(setup);
  harness.render();
  BackWallIndirect wall{harness.output("indirect"), {}, {}};
  const glm::ivec2 a = pixel_of(harness, wall.indirect, {0.06f, 0.36f, 0.5592f});
  const glm::ivec2 b = pixel_of(harness, wall.indirect, {0.50f, 0.50f, 0.5592f});
  wall.lo = glm::min(a, b);
  wall.hi = glm::max(a, b);
  return wall;
}

// The mean step between pixels two apart that straddle an 8 x 8 workgroup's edge, against the
// mean step between pixels two apart inside one.
void expect_no_workgroup_seams(const BackWallIndirect& wall) {
  double across = 0.0, inside = 0.0;
  int steps_across = 0, steps_inside = 0;
  for (int y = wall.lo.y; y <= wall.hi.y; ++y) {
    for (int x = wall.lo.x; x + 2 <= wall.hi.x; ++x) {
      const double step = std::abs(wall.luminance(x + 2, y) - wall.luminance(x, y));
      if (x % 8 == 6) {  // x + 2 is the next workgroup's first column
        across += step;
        ++steps_across;
      } else if (x % 8 == 2) {
        inside += step;
        ++steps_inside;
      }
    }
  }
  across /= steps_across;
  inside /= steps_inside;
  std::printf(
      "back wall: mean two-pixel step across workgroup edges %.5f, inside %.5f (ratio %.2f)\n",
      across, inside, across / std::max(inside, 1e-12));
  EXPECT_GT(inside, 0.0);
  EXPECT_LT(across, 1.5 * inside);
}

// Mean one-pixel steps from even to odd coordinates against those from odd to even, along x
// and y.
void expect_no_two_pixel_pattern(const BackWallIndirect& wall) {
  for (int axis = 0; axis < 2; ++axis) {
    double from_even = 0.0, from_odd = 0.0;
    int count_even = 0, count_odd = 0;
    for (int y = wall.lo.y; y + (axis == 1 ? 1 : 0) <= wall.hi.y; ++y) {
      for (int x = wall.lo.x; x + (axis == 0 ? 1 : 0) <= wall.hi.x; ++x) {
        const int next_x = axis == 0 ? x + 1 : x, next_y = axis == 1 ? y + 1 : y;
        const double step = std::abs(wall.luminance(next_x, next_y) - wall.luminance(x, y));
        if ((axis == 0 ? x : y) % 2 == 0) {
          from_even += step;
          ++count_even;
        } else {
          from_odd += step;
          ++count_odd;
        }
      }
    }
    from_even /= count_even;
    from_odd /= count_odd;
    const double ratio = from_even / std::max(from_odd, 1e-12);
    std::printf("back wall, %c: mean one-pixel step from even %.5f, from odd %.5f (ratio %.2f)\n",
                axis == 0 ? 'x' : 'y', from_even, from_odd, ratio);
    EXPECT_GT(from_odd, 0.0);
    EXPECT_LT(ratio, 1.4) << (axis == 0 ? "x" : "y");
    EXPECT_GT(ratio, 1.0 / 1.4) << (axis == 0 ? "x" : "y");
  }
}

// The interleaved average runs over the whole image, not inside each 8 x 8 workgroup: there the
// windows on either side of a workgroup's edge were disjoint, and the indirect light jumped at
// every eighth pixel (two-pixel steps across a workgroup's edge 1.70 times those inside one;
// 1.01 now). And every pixel's window is centred on it and slides by one pixel from one pixel
// to the next: an even window that reached back at even coordinates and ahead at odd ones gave
// each 2 x 2 block one window, so one value on a plane, the indirect light at half the
// resolution (one-pixel steps from odd to even coordinates were 0; the ratio of steps from even
// and from odd is 1.01 along x and 0.94 along y now). One render serves both checks.
TEST_F(VctGraphTest, InterleavedAverageLeavesNoWorkgroupSeamsAndNoTwoPixelPattern) {
  const BackWallIndirect wall = render_back_wall_indirect();
  ASSERT_GT(wall.hi.x - wall.lo.x, 24);
  ASSERT_GT(wall.hi.y - wall.lo.y, 8);
  expect_no_workgroup_seams(wall);
  expect_no_two_pixel_pattern(wall);
}

}  // namespace
}  // namespace voxgi::test
