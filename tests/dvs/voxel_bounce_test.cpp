// dvs.voxel_bounce chained with vct.filter on voxels uploaded directly: repeated bounces in a
// closed box converge monotonically towards Le / (1 - rho) with increments shrinking by about
// rho (a contraction), NaN/Inf never survives a feedback point, light leaking through a
// one-voxel wall into a dark second room stays below a stated bound, and unusable bindings
// are reported by pass and slot.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <memory>

#include <glm/gtc/packing.hpp>

#include "dvs_runner.hpp"
#include "engine/gpu/image.hpp"
#include "engine/scene/scene_builder.hpp"
#include "lighting_graph.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

constexpr uint32_t kRes = 32;
constexpr float kVoxel = 0.125f;

// The shell of the box |p| <= half (one voxel thick), normals pointing into the box.
VoxelValue box_shell(glm::vec3 c, float size, glm::vec3 lo, glm::vec3 hi, float albedo,
                     glm::vec3 emission) {
  VoxelValue v;
  const glm::vec3 inner_lo = lo + size, inner_hi = hi - size;
  const bool inside_outer = glm::all(glm::greaterThan(c, lo)) && glm::all(glm::lessThan(c, hi));
  const bool inside_inner =
      glm::all(glm::greaterThan(c, inner_lo)) && glm::all(glm::lessThan(c, inner_hi));
  if (!inside_outer || inside_inner) return v;
  glm::vec3 n(0.0f);
  for (int a = 0; a < 3; ++a) {
    if (c[a] < inner_lo[a]) n[a] += 1.0f;
    if (c[a] > inner_hi[a]) n[a] -= 1.0f;
  }
  v.albedo = glm::vec3(albedo);
  v.opacity = 1.0f;
  v.normal = glm::length(n) > 0.0f ? glm::normalize(n) : n;
  v.emission = emission;
  return v;
}

scene::Scene empty_scene() {
  scene::SceneBuilder builder("dvs-no-lights");
  builder.add_camera("camera", glm::vec3(0.0f, 0.0f, 3.0f), glm::vec3(0.0f), 0.8f);
  return builder.finish();
}

DvsRunner::Setup bounce_setup(scene::Scene scene, std::shared_ptr<VoxelSourceData> voxels,
                              int bounces, bool anisotropic, int max_bounces = 3,
                              const std::string& lighting = "\"occlusion\": \"voxel_rays\"") {
  DvsRunner::Setup setup;
  setup.graph_text = voxel_bounce_graph(kRes, 1, max_bounces, anisotropic, lighting);
  setup.scene = std::move(scene);
  setup.voxels = std::move(voxels);
  setup.overrides = {{"dvs.bounces", std::to_string(bounces)}};
  return setup;
}

// Mean radiance (green) of the wall voxels whose normal is a single axis (the faces, not the
// edges and corners), and the largest value of any voxel.
struct BoxStats {
  double face_mean = 0.0;
  float max = 0.0f;
  size_t non_finite = 0;
};

BoxStats box_stats(const VoxelGrid& grid, const std::vector<float>& radiance, glm::vec3 lo,
                   glm::vec3 hi) {
  BoxStats s;
  double sum = 0.0;
  size_t count = 0;
  const int r = static_cast<int>(grid.resolution());
  for (int z = 0; z < r; ++z) {
    for (int y = 0; y < r; ++y) {
      for (int x = 0; x < r; ++x) {
        const glm::ivec3 v(x, y, z);
        const glm::vec4 value = texel_rgba(radiance, grid.texel_index(0, v));
        for (int c = 0; c < 4; ++c) {
          if (!std::isfinite(value[c])) ++s.non_finite;
        }
        s.max = std::max(s.max, value.g);
        const VoxelValue want = box_shell(grid.center(0, v), kVoxel, lo, hi, 0.5f, glm::vec3(0));
        if (want.opacity == 0.0f) continue;
        const glm::vec3 n = glm::abs(want.normal);
        if (n.x + n.y + n.z != 1.0f) continue;
        sum += value.g;
        ++count;
      }
    }
  }
  s.face_mean = count ? sum / static_cast<double>(count) : 0.0;
  return s;
}

class BounceConvergenceTest : public GpuTest, public ::testing::WithParamInterface<bool> {};

// A closed box, albedo rho = 128/255, every wall voxel emitting Le = 1, no lights: the voxel
// radiance after K bounces is Le * sum_{j<=K} (rho g)^j, g <= 1 the share of the box the cone
// gather sees, so it rises monotonically, its increments shrink by rho g <= rho, and it never
// exceeds Le / (1 - rho). Measured on lavapipe: g = 0.98 with the anisotropic volumes (the
// graphs/dvs.json setting), 0.82 with the isotropic one (cones see through the box-filtered
// walls at coarse mips); 0.98 and 0.79 with one cone set for every voxel. Earlier, lower values
// and what raised them are in docs/error-budget.md (cones gathering the voxel's own surface;
// opacity read as coverage across a cone's travel, cone_trace_library_test,
// EmitterInTheWindowsOuterLayerIsSeen).
TEST_P(BounceConvergenceTest, RepeatedBouncesConvergeLikeAContraction) {
  const bool anisotropic = GetParam();
  const float rho = 128.0f / 255.0f;
  // The box fills the window but for one voxel, as the fitted volume of a closed scene does.
  const glm::vec3 lo(-1.875f), hi(1.875f);
  auto voxels = std::make_shared<VoxelSourceData>();
  voxels->grid = std::make_unique<VoxelGrid>(kRes, 1, kVoxel, glm::vec3(0.0f));
  voxels->grid->fill(
      [&](glm::vec3 c, float size) { return box_shell(c, size, lo, hi, 0.5f, glm::vec3(1.0f)); });
  const int max_bounces = 5;
  std::vector<double> means;
  for (int k = 0; k <= max_bounces; ++k) {
    DvsRunner runner(bounce_setup(empty_scene(), voxels, k, anisotropic, max_bounces));
    runner.render();
    const BoxStats s = box_stats(*voxels->grid, runner.read("radiance"), lo, hi);
    EXPECT_EQ(s.non_finite, 0u);
    EXPECT_LE(s.max, 1.0f / (1.0f - rho) * 1.001f) << "energy created after " << k << " bounces";
    means.push_back(s.face_mean);
  }
  const double limit = 1.0 / (1.0 - rho);
  std::cout << (anisotropic ? "anisotropic" : "isotropic") << " face mean by bounce:";
  for (double m : means) std::cout << " " << m;
  std::cout << " (Le/(1-rho) = " << limit << ")\n  increment ratios:";
  EXPECT_NEAR(means[0], 1.0, 1e-3) << "0 bounces: emission only";
  for (size_t k = 1; k < means.size(); ++k) {
    EXPECT_GT(means[k], means[k - 1]) << "not monotonic at bounce " << k;
    if (k >= 2) {
      const double ratio = (means[k] - means[k - 1]) / (means[k - 1] - means[k - 2]);
      std::cout << " " << ratio;
      EXPECT_LT(ratio, rho + 0.02) << "increments do not shrink by rho at bounce " << k;
    }
  }
  std::cout << "\n";
  const double gain = (means[1] - means[0]) / rho;  // g: the gather's share of the walls
  std::cout << "  gather gain g = " << gain << ", limit Le/(1-rho g) = " << 1.0 / (1.0 - rho * gain)
            << "\n";
  EXPECT_GT(gain, anisotropic ? 0.65 : 0.2)
      << "the first bounce gathers too little of a closed box";
  EXPECT_LT(gain, 1.0);
  // A linear contraction makes the sequence geometric: with q the mean increment ratio, the
  // result after 5 bounces is within q^5 of Le + (first increment) / (1 - q).
  double q = 0.0;
  for (size_t k = 2; k < means.size(); ++k) {
    q += (means[k] - means[k - 1]) / (means[k - 1] - means[k - 2]) / (means.size() - 2.0);
  }
  const double geometric_limit = means[0] + (means[1] - means[0]) / (1.0 - q);
  std::cout << "  mean ratio q = " << q << ", geometric limit " << geometric_limit << "\n";
  EXPECT_NEAR(means.back(), geometric_limit, 0.02 * geometric_limit);
  EXPECT_LT(means.back(), limit);
}

INSTANTIATE_TEST_SUITE_P(Filter, BounceConvergenceTest, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& param) {
                           return std::string(param.param ? "anisotropic" : "isotropic");
                         });

// NaN and Inf in the voxel inputs never reach the radiance volume, and a NaN planted in the
// radiance volume is gone after the next frame that re-lights.
TEST_F(GpuTest, NonFiniteValuesDoNotSurviveAFeedbackPoint) {
  const glm::vec3 lo(-1.25f), hi(1.25f);
  auto voxels = std::make_shared<VoxelSourceData>();
  voxels->grid = std::make_unique<VoxelGrid>(kRes, 1, kVoxel, glm::vec3(0.0f));
  voxels->grid->fill(
      [&](glm::vec3 c, float size) { return box_shell(c, size, lo, hi, 0.5f, glm::vec3(0.2f)); });
  const float nan = std::nanf("");
  const float inf = std::numeric_limits<float>::infinity();
  VoxelValue bad{glm::vec3(0.5f), 1.0f, glm::vec3(nan, 1.0f, 0.0f), glm::vec3(nan, inf, 1.0f)};
  voxels->grid->set(0, voxels->grid->window_voxel_at(0, {0.0f, -1.2f, 0.0f}), bad);
  bad.normal = glm::vec3(inf, 0.0f, 0.0f);
  voxels->grid->set(0, voxels->grid->window_voxel_at(0, {0.3f, 1.2f, 0.0f}), bad);

  scene::SceneBuilder builder("dvs-nan");
  scene::Light light;
  light.intensity = 5.0f;
  builder.add_light(light, glm::vec3(0.2f, 0.5f, 0.1f));
  DvsRunner runner(bounce_setup(builder.finish(), voxels, 2, true));
  auto count_bad = [&](const std::vector<float>& values) {
    size_t n = 0;
    for (float v : values) n += std::isfinite(v) && v >= 0.0f ? 0 : 1;
    return n;
  };
  runner.render();
  const std::vector<float> first = runner.read("radiance");
  EXPECT_EQ(count_bad(first), 0u) << "non-finite voxel inputs reached the radiance volume";

  // Plant NaN in the persistent radiance volume (the state a bad write would leave).
  gpu::Image* image = runner.executor().image("dvs.radiance");
  ASSERT_NE(image, nullptr);
  std::vector<uint16_t> texels(first.size());
  for (size_t i = 0; i < first.size(); ++i) texels[i] = glm::packHalf1x16(first[i]);
  for (size_t i = 0; i < texels.size(); i += 97) texels[i] = 0x7e00;  // half NaN
  image->upload_mip(texels.data(), texels.size() * 2, 0, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  ASSERT_GT(count_bad(runner.read("radiance")), 0u);
  runner.move_light(0, glm::vec3(-0.2f, 0.4f, 0.0f));
  runner.render(/*lights_changed=*/true);
  EXPECT_EQ(count_bad(runner.read("radiance")), 0u) << "a NaN survived a frame";
}

// Two rooms (1.56 x 1.5 x 1.5 m closed boxes) sharing a one-voxel wall, a point light only in
// the first. The leak metric is the mean radiance of the second room's walls over the first
// room's, after two bounces. Measured: 0.051 with the default kappa 8 (the soft voxel shadows
// let some direct light through a thin wall far from the light), 0.029 with kappa 64.
TEST_F(GpuTest, LightLeakingThroughAOneVoxelWallStaysBelowBound) {
  const glm::vec3 lo1(-1.5f, -0.75f, -0.75f), hi1(0.0625f, 0.75f, 0.75f);
  const glm::vec3 lo2(-0.0625f, -0.75f, -0.75f), hi2(1.5f, 0.75f, 0.75f);
  auto voxels = std::make_shared<VoxelSourceData>();
  voxels->grid = std::make_unique<VoxelGrid>(kRes, 1, kVoxel, glm::vec3(0.0f));
  voxels->grid->fill([&](glm::vec3 c, float size) {
    VoxelValue a = box_shell(c, size, lo1, hi1, 0.7f, glm::vec3(0.0f));
    const VoxelValue b = box_shell(c, size, lo2, hi2, 0.7f, glm::vec3(0.0f));
    if (a.opacity > 0.0f && b.opacity > 0.0f) {
      a.normal = glm::vec3(0.0f);  // the shared wall: both faces in one voxel cancel
    } else if (b.opacity > 0.0f) {
      a = b;
    }
    return a;
  });
  scene::SceneBuilder builder("dvs-two-rooms");
  scene::Light light;
  light.intensity = 10.0f;
  builder.add_light(light, glm::vec3(-0.75f, 0.2f, 0.0f));
  const scene::Scene scene = builder.finish();
  for (const char* kappa : {"8", "64"}) {
    DvsRunner runner(
        bounce_setup(scene, voxels, 2, true, 3,
                     std::string("\"occlusion\": \"voxel_rays\", \"shadow_kappa\": ") + kappa));
    runner.render();
    const std::vector<float> radiance = runner.read("radiance");
    const VoxelGrid& grid = *voxels->grid;
    double room1 = 0.0, room2 = 0.0;
    size_t n1 = 0, n2 = 0;
    const int r = static_cast<int>(kRes);
    for (int z = 0; z < r; ++z) {
      for (int y = 0; y < r; ++y) {
        for (int x = 0; x < r; ++x) {
          const glm::vec3 c = grid.center(0, {x, y, z});
          const float g = texel_rgba(radiance, grid.texel_index(0, {x, y, z})).g;
          if (box_shell(c, kVoxel, lo1, hi1, 1, {}).opacity > 0.0f && c.x < -0.1f) {
            room1 += g;
            ++n1;
          } else if (box_shell(c, kVoxel, lo2, hi2, 1, {}).opacity > 0.0f && c.x > 0.1f) {
            room2 += g;
            ++n2;
          }
        }
      }
    }
    const double leak = (room2 / static_cast<double>(n2)) / (room1 / static_cast<double>(n1));
    std::cout << "kappa " << kappa << ": room 1 mean " << room1 / static_cast<double>(n1)
              << ", room 2 mean " << room2 / static_cast<double>(n2) << ", leak " << leak << "\n";
    EXPECT_LT(leak, std::string(kappa) == "64" ? 0.05 : 0.08) << "kappa " << kappa;
  }
}

}  // namespace
}  // namespace voxgi::test

namespace voxgi::test {
namespace {

// Bindings the passes cannot work with are reported naming the pass and the slots, not
// crashed on: a bounce with only some of the directional volumes, and voxel volumes of a
// different size than the radiance clipmap.
TEST_F(GpuTest, BadBindingsAreReportedByPassAndSlot) {
  auto voxels = std::make_shared<VoxelSourceData>();
  voxels->grid = std::make_unique<VoxelGrid>(kRes, 1, kVoxel, glm::vec3(0.0f));
  std::string graph = voxel_bounce_graph(kRes, 1, 1, true, "");
  const std::string six = "\"neg_z\": \"vct.neg_z\" }, \"out\"";
  const size_t bounce = graph.find("dvs.voxel_bounce");
  const size_t at = graph.find(six, bounce);
  ASSERT_NE(at, std::string::npos);
  // Drop the bounce's "neg_z" binding: five of six directional volumes.
  const size_t start = graph.rfind(", \"neg_z\"", at + 1);
  graph.erase(start, at + std::string("\"neg_z\": \"vct.neg_z\"").size() - start);
  DvsRunner::Setup setup;
  setup.graph_text = graph;
  setup.scene = empty_scene();
  setup.voxels = voxels;
  setup.overrides = {{"dvs.bounces", "1"}};
  try {
    DvsRunner runner(std::move(setup));
    runner.render();
    FAIL() << "a bounce with five directional volumes was accepted";
  } catch (const std::exception& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("bounce1"), std::string::npos) << message;
    EXPECT_NE(message.find("pos_x"), std::string::npos) << message;
    std::cout << "error: " << message << "\n";
  }

  std::string mismatched = voxel_lighting_graph(kRes, 1, "");
  const std::string radiance =
      "\"dvs.radiance\": { \"format\": \"rgba16f\", \"mips\": \"full\", "
      "\"type\": \"clipmap\", \"resolution\": " +
      std::to_string(kRes);
  const size_t r = mismatched.find(radiance);
  ASSERT_NE(r, std::string::npos);
  mismatched.replace(r, radiance.size(),
                     "\"dvs.radiance\": { \"format\": \"rgba16f\", \"mips\": \"full\", "
                     "\"type\": \"clipmap\", \"resolution\": 16");
  DvsRunner::Setup lighting;
  lighting.graph_text = mismatched;
  lighting.scene = empty_scene();
  lighting.voxels = voxels;
  try {
    DvsRunner runner(std::move(lighting));
    runner.render();
    FAIL() << "voxel volumes of another size than the radiance clipmap were accepted";
  } catch (const std::exception& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("voxel_lighting"), std::string::npos) << message;
    EXPECT_NE(message.find("albedo"), std::string::npos) << message;
    std::cout << "error: " << message << "\n";
  }
}

}  // namespace
}  // namespace voxgi::test
