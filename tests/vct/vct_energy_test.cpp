// graphs/vct.json end to end (voxelization, injection, anisotropic filtering, cone gather) against
// indirect light that does not come from the renderer: a receiver facing a lit square (closed
// form under a directional light, a numerical integral under a point light), a closed box
// (radiosity), and the path tracer limited to one indirect bounce on the Cornell box and a thin
// wall. References and scenes: tests/common/gi_energy.

#include <gtest/gtest.h>

#include <string>
#include <tuple>

#include "tests/common/gi_energy.hpp"
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

TEST_P(VctAnalyticTest, ClosedBoxUnderAPointLight) {
  expect_lit_box_matches_radiosity(vct_gi_setup(GetParam()), BoxRadiosity(12, 1));
}

INSTANTIATE_TEST_SUITE_P(Voxels, VctAnalyticTest, ::testing::Values(32u, 64u),
                         [](const auto& param_info) {
                           return voxel_resolution_name(param_info.param);
                         });

// (scene index in energy_bound_scenes(), voxel resolution)
class VctEnergyBoundTest : public GpuTest,
                           public ::testing::WithParamInterface<std::tuple<size_t, uint32_t>> {};

// One render per cone count: the cone count is a live parameter, so injection and filtering
// run once and only the gather runs again.
TEST_P(VctEnergyBoundTest, IndirectStaysWithinThePathTracedOneBounce) {
  const auto [scene_index, resolution] = GetParam();
  const EnergyBoundScene bound_scene = energy_bound_scenes().at(scene_index);
  const scene::Scene scene = bound_scene.make();
  const PathTracedMean reference =
      path_traced_mean_indirect(scene, kEnergyBoundImageSize, 1, kEnergyBoundSamplesPerPixel);
  RenderHarness harness(
      voxel_gi_render_setup(vct_gi_setup(resolution), scene, kEnergyBoundImageSize));
  for (int cones : {4, 9, 16}) {
    harness.executor().set_param("cone_trace.diffuse_cones", std::to_string(cones));
    harness.render();
    const std::string label =
        std::string(bound_scene.name) + ", " + vct_gi_setup(resolution, cones).label;
    const RenderedImage indirect = harness.output("indirect");
    expect_finite_non_negative(indirect, label);
    expect_within_energy_bound(label, mean_luminance(indirect), reference, bound_scene.tolerance);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Voxels, VctEnergyBoundTest,
    ::testing::Combine(::testing::Range(size_t{0}, energy_bound_scenes().size()),
                       ::testing::Values(32u, 64u)),
    [](const auto& param_info) {
      return std::string(energy_bound_scenes().at(std::get<0>(param_info.param)).name) + "_" +
             voxel_resolution_name(std::get<1>(param_info.param));
    });

}  // namespace
}  // namespace voxgi::test
