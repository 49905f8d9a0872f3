// graphs/vct.json end to end (voxelization, injection, anisotropic filtering, cone gather) against
// indirect light that does not come from the renderer: a receiver facing a lit square (closed
// form under a directional light, a numerical integral under a point light), a closed box
// (radiosity), and the path tracer limited to one indirect bounce on the Cornell box and a thin
// wall. References and scenes: tests/common/gi_energy.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <tuple>

#include "engine/image/metrics.hpp"
#include "engine/scene/scene_builder.hpp"
#include "tests/common/gi_energy.hpp"
#include "tests/common/hard_case_scenes.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

class VctAnalyticTest : public GpuTest, public ::testing::WithParamInterface<uint32_t> {};

TEST_P(VctAnalyticTest, ReceiverOverASquareUnderADirectionalLight) {
  expect_lit_square_matches_closed_form(vct_gi_setup(GetParam()), SquareLight::Directional);
}

TEST_P(VctAnalyticTest, ReceiverOverASquareUnderAPointLight) {
  expect_lit_square_matches_closed_form(vct_gi_setup(GetParam()), SquareLight::Point);
}

TEST_P(VctAnalyticTest, ReceiverBeforeALitWall) {
  expect_receiver_before_a_lit_wall_matches_closed_form(vct_gi_setup(GetParam()));
}

// A cone sees a voxel's light only from the side its surface faces (contracts/cone_trace.glsl,
// vct_facing): under the square, in its shadow, nothing comes down through it.
TEST_P(VctAnalyticTest, ReceiverUnderASquareGetsNoLightThroughIt) {
  expect_unlit_underside_sends_nothing(vct_gi_setup(GetParam()), SquareLight::Directional);
}

// Both faces of a thin wall in one voxel, lit on one side: the voxel sends its lit face's
// light to the lit side only (docs/error-budget.md, nineteenth round).
TEST_P(VctAnalyticTest, ThinWallInOneVoxelSendsNothingThrough) {
  expect_thin_wall_in_one_voxel_sends_nothing_through(vct_gi_setup(GetParam()));
}

TEST_P(VctAnalyticTest, ClosedBoxUnderAPointLight) {
  expect_lit_box_matches_radiosity(vct_gi_setup(GetParam()), BoxRadiosity(12, 1));
}

INSTANTIATE_TEST_SUITE_P(Voxels, VctAnalyticTest, ::testing::Values(32u, 64u),
                         [](const auto& param_info) {
                           return voxel_resolution_name(param_info.param);
                         });

// The same cases in vct.filter's front-light mode (graphs/vct_front_light.json), and one it is
// for: a receiver below the square's level and beside it looks up at the unlit underside
// through the sideways volumes, which there hold only the light of surfaces facing sideways.
// The point-lit square is left out: the mode changes the filter and the reads, not the
// injection, which the landed mode's point-lit squares test.
class VctFrontLightAnalyticTest : public GpuTest, public ::testing::WithParamInterface<uint32_t> {};

TEST_P(VctFrontLightAnalyticTest, ReceiverOverASquareUnderADirectionalLight) {
  expect_lit_square_matches_closed_form(vct_front_light_gi_setup(GetParam()),
                                        SquareLight::Directional);
}

TEST_P(VctFrontLightAnalyticTest, ReceiverBeforeALitWall) {
  expect_receiver_before_a_lit_wall_matches_closed_form(vct_front_light_gi_setup(GetParam()));
}

TEST_P(VctFrontLightAnalyticTest, ReceiverUnderASquareGetsNoLightThroughIt) {
  expect_unlit_underside_sends_nothing(vct_front_light_gi_setup(GetParam()),
                                       SquareLight::Directional);
}

TEST_P(VctFrontLightAnalyticTest, ThinWallInOneVoxelSendsNothingThrough) {
  expect_thin_wall_in_one_voxel_sends_nothing_through(vct_front_light_gi_setup(GetParam()));
}

TEST_P(VctFrontLightAnalyticTest, ClosedBoxUnderAPointLight) {
  expect_lit_box_matches_radiosity(vct_front_light_gi_setup(GetParam()), BoxRadiosity(12, 1));
}

// At 32^3 only: the mode's closed forms move with the resolution as the landed mode's do.
INSTANTIATE_TEST_SUITE_P(Voxels, VctFrontLightAnalyticTest, ::testing::Values(32u),
                         [](const auto& param_info) {
                           return voxel_resolution_name(param_info.param);
                         });

// The case the mode is for, at both resolutions (graphs/vct.json fails it: kBesideCases).
class VctFrontLightSidewaysTest : public GpuTest, public ::testing::WithParamInterface<uint32_t> {};

TEST_P(VctFrontLightSidewaysTest, ReceiverBesideAndBelowASquareGetsNoLightFromIt) {
  expect_unlit_underside_sends_nothing_sideways(vct_front_light_gi_setup(GetParam()));
}

INSTANTIATE_TEST_SUITE_P(Voxels, VctFrontLightSidewaysTest, ::testing::Values(32u, 64u),
                         [](const auto& param_info) {
                           return voxel_resolution_name(param_info.param);
                         });

// Nothing may assume metres: the same square modelled in millimetres (glTF files in other
// units are common) gets the same light. Cones used to stop after 100 units, which left the
// receiver at 0.25 m (250 units) without the square's light.
class VctSceneUnitsTest : public GpuTest {};

TEST_F(VctSceneUnitsTest, ReceiverOverASquareModelledInMillimetres) {
  expect_lit_square_matches_closed_form(vct_gi_setup(32), SquareLight::Directional,
                                        kLitSquareTolerance, 1000.0);
}

// (scene index in energy_bound_scenes(), voxel resolution)
class VctEnergyBoundTest : public GpuTest,
                           public ::testing::WithParamInterface<std::tuple<size_t, uint32_t>> {};

// One render per cone count: the cone count is a live parameter, so injection and filtering
// run once and only the gather runs again. setup(0) keeps the graph's cone count.
void expect_every_cone_count_within_the_bound(
    size_t scene_index, const std::function<VoxelGiSetup(int diffuse_cones)>& setup) {
  const EnergyBoundScene bound_scene = energy_bound_scenes().at(scene_index);
  const scene::Scene scene = bound_scene.make();
  const PathTracedMean reference =
      path_traced_mean_indirect(scene, kEnergyBoundImageSize, 1, kEnergyBoundSamplesPerPixel);
  RenderHarness harness(voxel_gi_render_setup(setup(0), scene, kEnergyBoundImageSize));
  for (int cones : {4, 9, 16}) {
    harness.executor().set_param("cone_trace.diffuse_cones", std::to_string(cones));
    harness.render();
    const std::string label = std::string(bound_scene.name) + ", " + setup(cones).label;
    const RenderedImage indirect = harness.output("indirect");
    expect_finite_non_negative(indirect, label);
    expect_within_energy_bound(label, mean_luminance(indirect), reference, bound_scene.tolerance);
  }
}

TEST_P(VctEnergyBoundTest, IndirectStaysWithinThePathTracedOneBounce) {
  const auto [scene_index, resolution] = GetParam();
  expect_every_cone_count_within_the_bound(
      scene_index, [&](int cones) { return vct_gi_setup(resolution, cones); });
}

// The same bound in vct.filter's front-light mode: light read over the facing shares (a
// division) must not return more than the path tracer either.
class VctFrontLightEnergyBoundTest : public GpuTest,
                                     public ::testing::WithParamInterface<size_t> {};

TEST_P(VctFrontLightEnergyBoundTest, IndirectStaysWithinThePathTracedOneBounce) {
  expect_every_cone_count_within_the_bound(
      GetParam(), [](int cones) { return vct_front_light_gi_setup(32u, cones); });
}

INSTANTIATE_TEST_SUITE_P(Voxels, VctFrontLightEnergyBoundTest,
                         ::testing::Range(size_t{0}, energy_bound_scenes().size()),
                         [](const auto& param_info) {
                           return std::string(energy_bound_scenes().at(param_info.param).name);
                         });

// The same bound at every other setting of the cones' refinement where they meet a surface
// (cone_trace.refine; the test above runs the default, 2): off, surfaces stop cones a voxel
// early; refined further, they stop them later, so more of the light beyond reaches them, and
// that must not become more than the path tracer's.
class VctRefinedEnergyBoundTest : public GpuTest, public ::testing::WithParamInterface<size_t> {};

TEST_P(VctRefinedEnergyBoundTest, IndirectStaysWithinThePathTracedOneBounce) {
  const EnergyBoundScene bound_scene = energy_bound_scenes().at(GetParam());
  const scene::Scene scene = bound_scene.make();
  const PathTracedMean reference =
      path_traced_mean_indirect(scene, kEnergyBoundImageSize, 1, kEnergyBoundSamplesPerPixel);
  const VoxelGiSetup gi = vct_gi_setup(32u, 9);
  RenderHarness harness(voxel_gi_render_setup(gi, scene, kEnergyBoundImageSize));
  for (int refine : {0, 1, 3}) {
    harness.executor().set_param("cone_trace.refine", std::to_string(refine));
    harness.render();
    const std::string label =
        std::string(bound_scene.name) + ", " + gi.label + ", refine " + std::to_string(refine);
    const RenderedImage indirect = harness.output("indirect");
    expect_finite_non_negative(indirect, label);
    expect_within_energy_bound(label, mean_luminance(indirect), reference, bound_scene.tolerance);
  }
}

INSTANTIATE_TEST_SUITE_P(Voxels, VctRefinedEnergyBoundTest,
                         ::testing::Range(size_t{0}, energy_bound_scenes().size()),
                         [](const auto& param_info) {
                           return std::string(energy_bound_scenes().at(param_info.param).name);
                         });

INSTANTIATE_TEST_SUITE_P(
    Voxels, VctEnergyBoundTest,
    ::testing::Combine(::testing::Range(size_t{0}, energy_bound_scenes().size()),
                       ::testing::Values(32u, 64u)),
    [](const auto& param_info) {
      return std::string(energy_bound_scenes().at(std::get<0>(param_info.param)).name) + "_" +
             voxel_resolution_name(std::get<1>(param_info.param));
    });

// A floor lit only by an emitting square above it, seen from a camera straight above.
struct FloorUnderAnEmitter {
  static constexpr float kFloorAlbedo = 0.8f;
  static constexpr float kRadiance = 10.0f;
  static constexpr float kSide = 0.2f;
  static constexpr float kHeight = 0.25f;
  static constexpr float kCameraHeight = 1.2f;
  static constexpr float kViewHalfWidth = 0.45f;  // on the floor
};

// The emitting square: its centre's (x, z) and its side.
struct EmitterPlacement {
  glm::vec2 centre{0.25f, 0.0f};
  float side = FloorUnderAnEmitter::kSide;
};

// The default square turned 90 degrees about the vertical through the floor's centre ((x, z) ->
// (z, -x)). The voxel grid (anchored on whole voxels) and the camera's view of the floor map
// onto themselves; only the emitter's azimuth, seen from the floor, turns. One cone frame for
// the whole floor sees the two scenes from different azimuths, and a few cones miss the emitter
// differently (docs/vct.md, "Interleaved cone sets"); the interleaved gather averages turns
// that a quarter turn maps onto themselves, so the two means must agree.
constexpr EmitterPlacement kTurnedEmitter{{0.0f, -0.25f}, FloorUnderAnEmitter::kSide};
// A square as wide as the view, centred: most of the floor's light comes from high above it.
constexpr EmitterPlacement kWideEmitter{{0.0f, 0.0f}, 0.6f};

scene::Scene floor_under_an_emitter(const EmitterPlacement& emitter = {}) {
  scene::SceneBuilder b("floor_under_an_emitter");
  using S = FloorUnderAnEmitter;
  const int floor = b.add_material(matte(glm::vec3(S::kFloorAlbedo)));
  const int lamp = b.add_material(matte(glm::vec3(0.0f), glm::vec3(S::kRadiance)));
  b.add_quad("floor", {-0.5f, 0.0f, -0.5f}, {0.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 0.0f}, floor);
  const glm::vec2 centre = emitter.centre;
  const float side = emitter.side;
  const float height = S::kHeight;
  // Facing -y, towards the floor.
  b.add_quad("emitter", {centre.x - 0.5f * side, height, centre.y - 0.5f * side},
             {side, 0.0f, 0.0f}, {0.0f, 0.0f, side}, lamp);
  const float distance = S::kCameraHeight;
  b.add_camera("above", {0.0f, distance, 0.0f}, {0.0f, 0.0f, 0.0f},
               2.0f * std::atan(S::kViewHalfWidth / distance), {0.0f, 0.0f, 1.0f});
  return b.finish();
}

TEST_F(GpuTest, InterleavedConeSetsDoNotDependOnTheFramesAzimuth) {
  double mean[2][2][2];  // [turned][interleaved][cones 4, 6]
  for (int turned = 0; turned < 2; ++turned) {
    RenderHarness harness(voxel_gi_render_setup(
        vct_gi_setup(32), floor_under_an_emitter(turned != 0 ? kTurnedEmitter : EmitterPlacement{}),
        kEnergyBoundImageSize));
    for (int interleaved = 0; interleaved < 2; ++interleaved) {
      harness.executor().set_param("cone_trace.interleave", interleaved != 0 ? "4" : "1");
      for (int c = 0; c < 2; ++c) {
        harness.executor().set_param("cone_trace.diffuse_cones", c == 0 ? "4" : "6");
        harness.render();
        const RenderedImage indirect = harness.output("indirect");
        expect_finite_non_negative(indirect, "floor under an emitter");
        mean[turned][interleaved][c] = mean_luminance(indirect);
      }
    }
  }
  for (int c = 0; c < 2; ++c) {
    const double one_frame = mean[1][0][c] / mean[0][0][c];
    const double interleaved = mean[1][1][c] / mean[0][1][c];
    std::printf(
        "[frame] %d cones: turned / plain mean indirect %.4f with one frame, %.4f interleaved "
        "(plain %.5f, %.5f)\n",
        c == 0 ? 4 : 6, one_frame, interleaved, mean[0][0][c], mean[0][1][c]);
    EXPECT_NEAR(interleaved, 1.0, 0.02) << (c == 0 ? 4 : 6) << " cones";
  }
}

// The floor's one-bounce light from the emitter in closed form: at each pixel centre's floor
// point, rho L F with F the point-to-square form factor (the emitter is one-sided and seen from
// its back, so every pixel sees the floor).
double floor_under_an_emitter_mean_indirect(uint32_t size, const EmitterPlacement& emitter = {}) {
  using S = FloorUnderAnEmitter;
  const double x0 = emitter.centre.x - 0.5 * emitter.side;
  const double x1 = emitter.centre.x + 0.5 * emitter.side;
  const double z0 = emitter.centre.y - 0.5 * emitter.side;
  const double z1 = emitter.centre.y + 0.5 * emitter.side;
  const glm::dvec3 square[4] = {
      {x0, S::kHeight, z0}, {x1, S::kHeight, z0}, {x1, S::kHeight, z1}, {x0, S::kHeight, z1}};
  const CameraPixelRays rays(floor_under_an_emitter(emitter).cameras.front(), size);
  double sum = 0.0;
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) {
      const auto [origin, direction] = rays(x, y);
      const glm::dvec3 floor_point = origin - (origin.y / direction.y) * direction;
      sum += S::kFloorAlbedo * S::kRadiance *
             polygon_form_factor(floor_point, glm::dvec3(0.0, 1.0, 0.0), square);
    }
  }
  return sum / (static_cast<double>(size) * size);
}

// End to end through the voxelization of an emitter, its injection as emission, the filter and
// the gather: the near field of a small emitter. Measured with the default 6 cones: 1.35x the
// closed form at 32^3 and 1.18x at 64^3 (1.23x and 1.13x at the eleventh round). It was 1.63x
// and 1.45x while the gather interpolated optical depth across a cone's travel too, which made a
// texel half covered by the emitter nearly opaque and every emitter a voxel wider on each side
// (docs/error-budget.md, eleventh round). Held from both sides so that the excess cannot grow
// unseen; the target is 10%.
TEST_F(GpuTest, FloorUnderAnEmittingSquare) {
  const double expected = floor_under_an_emitter_mean_indirect(kEnergyBoundImageSize);
  for (uint32_t resolution : {32u, 64u}) {
    const double rendered = render_mean_indirect(vct_gi_setup(resolution), floor_under_an_emitter(),
                                                 kEnergyBoundImageSize);
    const double ratio = rendered / expected;
    std::printf("[emitting square] vct %u^3: %.5f against the closed form %.5f, ratio %.4f\n",
                resolution, rendered, expected, ratio);
    EXPECT_GT(ratio, 0.9) << resolution;
    EXPECT_LT(ratio, 1.35) << resolution;
  }
}

// A floor, an emitting square high above it and a wall standing between the square and the
// floor in front of the wall: as long as the floor is wide, kHeight high, its face at kFace (x)
// towards -x. The square (side kLampSide, its near edge kLampNear) faces the floor from
// kLampHeight, so that the floor at the wall's base would see it steeply past the wall's top.
struct WallBeforeTheEmitter {
  static constexpr float kFace = 0.05f;
  static constexpr float kThickness = 0.05f;
  static constexpr float kHeight = 0.3f;
  static constexpr float kLampHeight = 0.9f;
  static constexpr float kLampNear = 0.25f;
  static constexpr float kLampSide = 0.2f;
  // Floor points in front of the face closer than this see none of the square: a ray over the
  // wall's top edge from distance d meets the square's height at
  // kFace + d (kLampHeight / kHeight - 1), short of the square's near edge for every d <= 0.1.
  static constexpr float kHidden = 0.1f;
  static constexpr float kViewHalfWidth = 0.3f;  // on the floor, around the hidden strip
};

scene::Scene floor_behind_a_wall() {
  scene::SceneBuilder b("floor_behind_a_wall");
  using S = FloorUnderAnEmitter;
  using W = WallBeforeTheEmitter;
  const int floor = b.add_material(matte(glm::vec3(S::kFloorAlbedo)));
  const int lamp = b.add_material(matte(glm::vec3(0.0f), glm::vec3(S::kRadiance)));
  b.add_quad("floor", {-0.5f, 0.0f, -0.5f}, {0.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 0.0f}, floor);
  b.add_quad("emitter", {W::kLampNear, W::kLampHeight, -0.5f * W::kLampSide},
             {W::kLampSide, 0.0f, 0.0f}, {0.0f, 0.0f, W::kLampSide}, lamp);
  b.add_box("wall", {W::kFace + 0.5f * W::kThickness, 0.5f * W::kHeight, 0.0f},
            {W::kThickness, W::kHeight, 1.0f}, floor, 0.0f);
  b.add_camera("above", {0.0f, S::kCameraHeight, 0.0f}, {0.0f, 0.0f, 0.0f},
               2.0f * std::atan(W::kViewHalfWidth / S::kCameraHeight), {0.0f, 0.0f, 1.0f});
  return b.finish();
}

// The only light is the square's, which the wall hides from the floor in front of it: there the
// true one-bounce light is 0. Cones rising beside the wall must not read the square past it.
// Read at voxels as wide as the cone, whose filter reaches a cone radius beyond it, the strip
// got 0.070 / 0.046 (32^3 / 64^3) of the light the unhidden square would give it (the Cornell
// boxes' floors at the blocks' bases their ceiling light); read at voxels whose filter is as
// wide as the cone (or lane), 0.011 / 0.008 (docs/error-budget.md, thirtieth round).
TEST_F(GpuTest, WallHidesAnEmitterFromTheFloorAtItsBase) {
  using S = FloorUnderAnEmitter;
  using W = WallBeforeTheEmitter;
  const uint32_t size = kEnergyBoundImageSize;
  const scene::Scene scene = floor_behind_a_wall();
  const CameraPixelRays rays(scene.cameras.front(), size);
  const double x0 = W::kLampNear;
  const double x1 = W::kLampNear + W::kLampSide;
  const double z0 = -0.5 * W::kLampSide;
  const double z1 = 0.5 * W::kLampSide;
  const double h = W::kLampHeight;
  const glm::dvec3 square[4] = {{x0, h, z0}, {x1, h, z0}, {x1, h, z1}, {x0, h, z1}};
  for (uint32_t resolution : {32u, 64u}) {
    RenderHarness harness(voxel_gi_render_setup(vct_gi_setup(resolution), scene, size));
    harness.render();
    const RenderedImage indirect = harness.output("indirect");
    expect_finite_non_negative(indirect, "floor behind a wall");
    // The strip between 1 cm from the wall's face and the end of the hidden part, within the
    // square's width: rendered light against the light the square would give it unhidden.
    double rendered = 0.0;
    double unhidden = 0.0;
    int pixels = 0;
    for (uint32_t y = 0; y < size; ++y) {
      for (uint32_t x = 0; x < size; ++x) {
        const auto [origin, direction] = rays(x, y);
        const glm::dvec3 p = origin - (origin.y / direction.y) * direction;
        const double d = W::kFace - p.x;
        if (d < 0.01 || d > W::kHidden - 0.01 || p.z < z0 || p.z > z1) continue;
        rendered += image::luminance(&indirect.rgba[(static_cast<size_t>(y) * size + x) * 4]);
        unhidden += S::kFloorAlbedo * S::kRadiance *
                    polygon_form_factor(p, glm::dvec3(0.0, 1.0, 0.0), square);
        ++pixels;
      }
    }
    ASSERT_GT(pixels, 20) << resolution;
    const double leak = rendered / unhidden;
    std::printf(
        "[hidden emitter] vct %u^3: %d pixels at the wall's base get %.4f of the light "
        "the square gives them unhidden (true: 0)\n",
        resolution, pixels, leak);
    EXPECT_LT(leak, 0.025) << resolution;
  }
}

// The lanes of a capped cone spread its width at the axis's angle to the receiver (4 lanes) or
// in two rows just under and over it (8 lanes). Lanes offset along a straight tangent leaned
// towards the horizon, the more so the wider the cone, and took light that comes from high above
// away from every receiver: under this wide emitter 4 lanes gathered 0.960 / 0.971 of the axis
// alone at 4 / 6 cones, and the Cornell boxes were 5 to 15 points darker (docs/error-budget.md,
// fifth round); lanes at the axis's elevation gathered 0.997 / 1.000 of it. Rows whose lanes were
// each capped for their own height, or lifted for it, read the emitter 1.21-1.24x (twenty-eighth
// round). The closed form itself is exceeded (1.19x; 1.26x while optical depth was interpolated
// across the cones' travel, as for the small square above): the filter reaches past the
// emitter's edge. Lanes read voxels of their share of the cone's width, narrower than the axis
// alone reads, so they may gather a little less (4 / 8 lanes: 0.991 / 0.985 of the axis at
// 4 cones, 0.987 / 0.983 at 6; thirtieth round), never more, and not the 3-4% that leaning lost.
// Held from both sides so that the excess cannot grow unseen.
TEST_F(GpuTest, ConeLanesKeepTheAxisElevation) {
  const double expected = floor_under_an_emitter_mean_indirect(kEnergyBoundImageSize, kWideEmitter);
  RenderHarness harness(voxel_gi_render_setup(
      vct_gi_setup(32), floor_under_an_emitter(kWideEmitter), kEnergyBoundImageSize));
  const int lane_counts[] = {1, 4, 8};
  for (int cones : {4, 6}) {
    harness.executor().set_param("cone_trace.diffuse_cones", std::to_string(cones));
    double mean[3];
    for (int i = 0; i < 3; ++i) {
      harness.executor().set_param("cone_trace.lanes", std::to_string(lane_counts[i]));
      harness.render();
      const RenderedImage indirect = harness.output("indirect");
      expect_finite_non_negative(indirect, "floor under a wide emitter");
      mean[i] = mean_luminance(indirect);
    }
    std::printf(
        "[lanes] %d cones, wide emitter: 1 lane %.4f, 4 lanes %.4f, 8 lanes %.4f of the "
        "closed form %.5f\n",
        cones, mean[0] / expected, mean[1] / expected, mean[2] / expected, expected);
    for (int i : {1, 2}) {
      EXPECT_GT(mean[i] / mean[0], 0.975) << cones << " cones, " << lane_counts[i] << " lanes";
      EXPECT_LT(mean[i] / mean[0], 1.015) << cones << " cones, " << lane_counts[i] << " lanes";
    }
    for (double m : mean) {
      EXPECT_GT(m / expected, 0.9) << cones << " cones";
      EXPECT_LT(m / expected, 1.2) << cones << " cones";
    }
  }
}

}  // namespace
}  // namespace voxgi::test
