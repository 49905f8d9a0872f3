// graphs/lpv.json end to end (reflective shadow maps, injection, propagation, lookup) against
// indirect light that does not come from the renderer: a receiver facing a lit square (closed
// form under a directional light, a numerical integral under a point light), a closed box
// (radiosity), and the path tracer limited to one indirect bounce on the Cornell box and a thin
// wall. References and scenes: tests/common/gi_energy. One volume of 32^3 cells with the
// graph's 64 iterations; docs/lpv.md lists the measured ratios and their causes.

#include <gtest/gtest.h>

#include <string>

#include "tests/common/gi_energy.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

// Five octree levels over `resolution`^3 cells, 8 steps each (graphs/lpv.json's octree).
VoxelGiSetup lpv_octree_gi_setup(uint32_t resolution, const std::string& merge) {
  constexpr int kOctreeLevels = 5;
  VoxelGiSetup gi = lpv_gi_setup(resolution, 8);
  gi.overrides.insert_or_assign("lpv.octree_levels", std::to_string(kOctreeLevels));
  gi.overrides.insert_or_assign("propagate.merge", merge);
  gi.overrides.insert_or_assign("merge.merge", merge);
  gi.label += ", octree ";
  gi.label += merge;
  return gi;
}

// The receiver over the lit square: measured 0.45 to 0.78 of the closed form at 32^3. The
// light reaching the small receiver carries the two-band SH's negative back lobe of the
// square's light (docs/lpv.md, "Negative flux"), and the receiver's cell receives only the
// flux that steps across it. Held to 60% until the transport keeps its flux positive.
constexpr double kLpvLitSquareTolerance = 0.60;
// The closed box: measured 0.80 (0.50 to 0.90 by placement).
constexpr double kLpvBoxTolerance = 0.35;

TEST_F(GpuTest, LpvReceiverOverASquareUnderADirectionalLight) {
  expect_lit_square_matches_closed_form(lpv_gi_setup(32), SquareLight::Directional,
                                        kLpvLitSquareTolerance);
}

TEST_F(GpuTest, LpvReceiverOverASquareUnderAPointLight) {
  expect_lit_square_matches_closed_form(lpv_gi_setup(32), SquareLight::Point,
                                        kLpvLitSquareTolerance);
}

TEST_F(GpuTest, LpvClosedBoxUnderAPointLight) {
  expect_lit_box_matches_radiosity(lpv_gi_setup(32), BoxRadiosity(12, 1), kLpvBoxTolerance);
}

// The receiver over the lit square with two cascades around the camera (under the receiver):
// the finest cascade's window holds only part of the square; the rest comes from the coarser
// cascade's volume of the sources outside that window. Measured 0.56 to 0.61 (one level: 0.45
// to 0.54).
TEST_F(GpuTest, LpvReceiverOverASquareThroughTwoCascades) {
  VoxelGiSetup gi = lpv_gi_setup(32);
  gi.voxel_levels = 2;
  gi.label += ", 2 cascades";
  expect_lit_square_matches_closed_form(gi, SquareLight::Directional, kLpvLitSquareTolerance);
}

// The octree LPV (levels 32 to 2, 8 steps each, shells merge) over the lit square.
TEST_F(GpuTest, LpvOctreeReceiverOverASquareUnderADirectionalLight) {
  expect_lit_square_matches_closed_form(lpv_octree_gi_setup(32, "shells"), SquareLight::Directional,
                                        kLpvLitSquareTolerance);
}

// Three cascades around the camera under the receiver: the finest window holds none of the
// square, whose light reaches the receiver through the coarser levels' "outer" volumes.
// Measured 0.47 to 0.58 (0.03 when a pixel read its finest cascade alone).
TEST_F(GpuTest, LpvReceiverOverASquareThroughThreeCascades) {
  VoxelGiSetup gi = lpv_gi_setup(32);
  gi.voxel_levels = 3;
  gi.label += ", 3 cascades";
  expect_lit_square_matches_closed_form(gi, SquareLight::Directional, kLpvLitSquareTolerance);
}

class LpvEnergyBoundTest : public GpuTest, public ::testing::WithParamInterface<size_t> {};

// The mean indirect luminance never more than kEnergyBoundTolerance above the path tracer
// limited to one bounce, at 16 and 64 iterations (measured on the Cornell box 0.36 and 0.84 of
// it: at 16 iterations the light has not crossed the room yet).
TEST_P(LpvEnergyBoundTest, IndirectStaysWithinThePathTracedOneBounce) {
  const EnergyBoundScene bound_scene = energy_bound_scenes().at(GetParam());
  const scene::Scene scene = bound_scene.make();
  const PathTracedMean reference =
      path_traced_mean_indirect(scene, kEnergyBoundImageSize, 1, kEnergyBoundSamplesPerPixel);
  for (const VoxelGiSetup& gi :
       {lpv_gi_setup(32, 16), lpv_gi_setup(32, 64), lpv_octree_gi_setup(32, "shells"),
        lpv_octree_gi_setup(32, "index")}) {
    const std::string label = std::string(bound_scene.name) + ", " + gi.label;
    RenderHarness harness(voxel_gi_render_setup(gi, scene, kEnergyBoundImageSize));
    harness.render();
    const RenderedImage indirect = harness.output("indirect");
    expect_finite_non_negative(indirect, label);
    expect_within_energy_bound(label, mean_luminance(indirect), reference, kEnergyBoundTolerance);
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, LpvEnergyBoundTest,
                         ::testing::Range<size_t>(0, energy_bound_scenes().size()),
                         [](const auto& param_info) {
                           return std::string(energy_bound_scenes().at(param_info.param).name);
                         });

}  // namespace
}  // namespace voxgi::test
