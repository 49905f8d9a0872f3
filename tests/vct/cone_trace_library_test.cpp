// Energy tests of contracts/cone_trace.glsl through vct.filter on volumes the test writes:
// a uniform emissive shell around a point gives irradiance pi*L for every cone count, an
// opaque wall stops a cone, and the step-size opacity correction makes results independent
// of the step factor.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "engine/scene/builtin_scenes.hpp"
#include "tests/gpu/gpu_test_env.hpp"
#include "tests/vct/filter_graphs.hpp"
#include "tests/vct/volume_harness.hpp"

namespace voxgi::test {
namespace {

constexpr int kR = 64;
constexpr float kVoxel = 1.0f / 16.0f;  // a 4 m dense volume around the origin

// Fills every level of `data` (centred near the origin) with radiance from `f` at the voxel
// centres.
template <typename F>
void fill_radiance(VolumeData& data, F f, int levels = 1) {
  data.info = make_clipmap_info(kR, levels, kVoxel, glm::vec3(0.3f, -0.2f, 0.1f));
  CpuClipmap radiance(kR, levels);
  for (int level = 0; level < levels; ++level) {
    const float size = data.info.levels[level].min_corner_size.w;
    for (int z = 0; z < kR; ++z) {
      for (int y = 0; y < kR; ++y) {
        for (int x = 0; x < kR; ++x) {
          const glm::ivec3 window(x, y, z);
          const glm::vec3 centre = glm::vec3(data.info.levels[level].min_corner_size) +
                                   (glm::vec3(window) + 0.5f) * size;
          radiance.at(clipmap_texel(data.info, window, level)) = f(centre);
        }
      }
    }
  }
  data.volumes["radiance"] = std::move(radiance);
  ++data.version;
}

// An opaque emitter (L = 1) filling the window layers x = first..last of one dense level.
VolumeData emitter_layers(const ClipmapInfo& info, int first, int last) {
  VolumeData data;
  data.info = info;
  CpuClipmap radiance(kR, 1);
  for (int z = 0; z < kR; ++z) {
    for (int y = 0; y < kR; ++y) {
      for (int x = first; x <= last; ++x) {
        radiance.at(clipmap_texel(data.info, {x, y, z}, 0)) = glm::vec4(1.0f);
      }
    }
  }
  data.volumes["radiance"] = std::move(radiance);
  ++data.version;
  return data;
}

// World position of a dense level's window corner.
glm::vec3 window_corner(const ClipmapInfo& info) {
  return glm::vec3(info.anchor) + glm::vec3(info.levels[0].min_corner_size);
}

class ConeTraceEnergyTest : public GpuTest, public ::testing::WithParamInterface<bool> {};
class ConeTraceClipmapTest : public GpuTest {};

// A point 1 m inside a uniform emitter: every voxel farther than 1 m is opaque and emits
// L = 1, so every direction of the hemisphere sees L and E = pi * L whatever the cone layout
// (the weights sum to pi). What is left is the transparency a cone keeps when it reaches the
// edge of the volume (2 m) through coarse mips that mix the emitter with the empty ball
// around the point. Tolerance: 5% for N >= 4 (the request of the issue), 10% below, where 1-3
// cones are wide (up to 60 degrees half angle); measured <= 0.6% for all N in both modes (the
// isotropic mode's 11% of an earlier filter is long gone, docs/error-budget.md).
TEST_P(ConeTraceEnergyTest, UniformEmissiveShellGivesPiL) {
  const bool anisotropic = GetParam();
  VolumeData data;
  fill_radiance(data, [](glm::vec3 c) {
    const float r = glm::length(c);
    return r >= 1.0f ? glm::vec4(1.0f, 1.0f, 1.0f, 1.0f) : glm::vec4(0.0f);
  });
  VolumeGraph graph(filter_graph(kR, 1, anisotropic), &data, scene::make_builtin_scene("empty"));
  graph.render();
  const std::vector<glm::vec3> normals = {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}, {0.6f, 0.48f, 0.64f}};
  std::printf("%s: N, E/(pi L) per normal, worst relative error\n",
              anisotropic ? "anisotropic" : "isotropic");
  for (int n = 1; n <= 16; ++n) {
    std::vector<Probe> probes;
    for (const glm::vec3& normal : normals) probes.push_back({glm::vec3(0.0f), normal});
    ProbeSettings s;
    s.diffuse_cones = n;
    s.anisotropic = anisotropic;
    const std::vector<ProbeResult> results =
        run_probes(graph, "voxel.clipmap_info", filtered_resources(anisotropic), probes, s);
    float worst = 0.0f;
    std::printf("  N=%2d:", n);
    for (const ProbeResult& r : results) {
      const float ratio = r.irradiance.g / static_cast<float>(M_PI);
      std::printf(" %.4f", ratio);
      worst = std::max(worst, std::abs(ratio - 1.0f));
      EXPECT_TRUE(std::isfinite(ratio));
    }
    std::printf("  error %.2f%%\n", 100.0f * worst);
    EXPECT_LT(worst, n >= 4 ? 0.05f : 0.10f) << "N = " << n;
  }
}

// One cone towards an opaque wall two voxels thick: fully occluded, and the radiance it
// returns is the wall's (L x opacity, since the wall is uniform).
TEST_P(ConeTraceEnergyTest, OpaqueWallStopsTheCone) {
  const bool anisotropic = GetParam();
  VolumeData data;
  fill_radiance(data, [](glm::vec3 c) {
    return c.x >= 0.5f && c.x <= 0.625f ? glm::vec4(2.0f, 2.0f, 2.0f, 1.0f) : glm::vec4(0.0f);
  });
  VolumeGraph graph(filter_graph(kR, 1, anisotropic), &data, scene::make_builtin_scene("empty"));
  graph.render();
  ProbeSettings s;
  s.single_cone = true;
  s.anisotropic = anisotropic;
  for (float tan_half : {0.05f, 0.2f, 0.577f}) {
    s.tan_half_angle = tan_half;
    const std::vector<ProbeResult> r =
        run_probes(graph, "voxel.clipmap_info", filtered_resources(anisotropic),
                   {{glm::vec3(0.0f), glm::vec3(1, 0, 0)}}, s);
    const float opacity = 1.0f - r[0].visibility;
    std::printf("tan %.3f: opacity %.4f radiance %.4f\n", tan_half, opacity, r[0].irradiance.r);
    // A narrow cone samples the wall at its own resolution and is stopped. Wider cones sample
    // mips where the 2-voxel wall fills part of a voxel: the directional volumes keep it
    // opaque along the axis (trilinear blending with the empty neighbour leaves a little),
    // the isotropic mips dilute it to 2/8 at mip 3, a known leak of isotropic filtering.
    const float required = tan_half <= 0.05f ? 0.99f : (anisotropic ? 0.9f : 0.15f);
    EXPECT_GE(opacity, required) << "tan(half angle) " << tan_half;
    EXPECT_NEAR(r[0].irradiance.r, 2.0f * opacity, 0.02f) << "tan(half angle) " << tan_half;
    // Away from the wall a narrow cone hits nothing (wide ones reach coarse mips that
    // contain the wall, as cone tracing should).
    if (tan_half > 0.2f) continue;
    s.max_distance = 1.5f;
    const std::vector<ProbeResult> away =
        run_probes(graph, "voxel.clipmap_info", filtered_resources(anisotropic),
                   {{glm::vec3(0.0f), glm::vec3(-1, 0, 0)}}, s);
    EXPECT_LT(1.0f - away[0].visibility, 0.02f) << "tan(half angle) " << tan_half;
    s.max_distance = 1e6f;
  }
}

// A narrow cone whose axis runs along the edge of an opaque wall one voxel thick (L = 2, the
// wall below y = 0, a voxel boundary): half of its cross-section meets the wall, so it must come
// out half blocked with half the wall's radiance, not blocked whole. The directional volumes
// average the opacities of texels side by side across the cone's travel (each covers its share
// of the cross-section); interpolating their optical depth (8 and 0 -> 4) made it 98% opaque,
// every surface a voxel wider on each side. Measured 0.50 (0.98 before).
TEST_F(ConeTraceClipmapTest, ConeAlongAWallsEdgeIsHalfBlocked) {
  VolumeData data;
  fill_radiance(data, [](glm::vec3 c) {
    const bool wall = c.x > 0.5f && c.x < 0.5f + kVoxel && c.y < 0.0f;
    return wall ? glm::vec4(2.0f, 2.0f, 2.0f, 1.0f) : glm::vec4(0.0f);
  });
  VolumeGraph graph(filter_graph(kR, 1, true), &data, scene::make_builtin_scene("empty"));
  graph.render();
  ProbeSettings s;
  s.single_cone = true;
  s.tan_half_angle = 0.02f;  // mip 0 at the wall
  const std::vector<ProbeResult> r =
      run_probes(graph, "voxel.clipmap_info", filtered_resources(true),
                 {{glm::vec3(0.0f, 0.0f, 0.1f), glm::vec3(1, 0, 0)}}, s);
  const float opacity = 1.0f - r[0].visibility;
  std::printf("cone along a wall's edge: opacity %.4f radiance %.4f\n", opacity, r[0].irradiance.r);
  EXPECT_NEAR(opacity, 0.5f, 0.05f);
  EXPECT_NEAR(r[0].irradiance.r, 2.0f * opacity, 0.02f);
}

// With VCT_LANE_ROWS_CELL (vct.cone_trace's lane_rows = cell) the lanes of a diffuse cone stand
// for its cell of the hemisphere: over the ring positions an interleaved window gives it
// (vct/interleave_layout.glsl), each band of elevation receives lanes in proportion to its
// cosine-weighted solid angle, so that the gather converges to the irradiance integral, and a
// cone can be checked against its own band of a path-traced reference. Bands of 0-10, 10-20,
// 20-30, 30-45, 45-60 and 60-90 degrees, 1024 ring positions (the turn does not change
// elevations), 8 lanes: measured within 0.2% of each band. The default rows, a quarter of the
// half angle under and over the axis (the lower one kept above 3/4 of its elevation), give the
// lowest band 0.88 of its share for 4, 9 and 16 cones, and the next 0.90 for 4 and 9
// (docs/error-budget.md, thirty-fifth round).
TEST_F(ConeTraceClipmapTest, LanesSampleTheirConesCells) {
  VolumeData data;
  fill_radiance(data, [](glm::vec3) { return glm::vec4(0.0f); });
  VolumeGraph graph(filter_graph(kR, 1, true), &data, scene::make_builtin_scene("empty"));
  graph.render();
  constexpr int kRings = 1024;
  constexpr int kLanes = 8;
  const float edges_deg[] = {0.0f, 10.0f, 20.0f, 30.0f, 45.0f, 60.0f, 90.0f};
  constexpr int kBands = 6;
  for (const int cones : {4, 9, 16}) {
    std::vector<Probe> probes;
    for (int ring = 0; ring < kRings; ++ring) {
      for (int cone = 0; cone < cones; ++cone) {
        for (int lane = 0; lane < kLanes; ++lane) {
          probes.push_back({glm::vec3(0.0f, (float(ring) + 0.5f) / kRings, float(cone)),
                            glm::vec3(float(lane), 0.0f, 0.0f)});
        }
      }
    }
    ProbeSettings s;
    s.lane_layout = true;
    s.diffuse_cones = cones;
    s.lanes = kLanes;
    const std::vector<ProbeResult> r =
        run_probes(graph, "voxel.clipmap_info", filtered_resources(true), probes, s);
    double band_weight[kBands] = {};
    double total = 0.0;
    for (const ProbeResult& lane : r) {
      const float elevation_deg =
          std::asin(std::clamp(lane.irradiance.z, 0.0f, 1.0f)) * 180.0f / float(M_PI);
      for (int b = 0; b < kBands; ++b) {
        if (elevation_deg >= edges_deg[b] && elevation_deg < edges_deg[b + 1]) {
          band_weight[b] += lane.visibility;
        }
      }
      total += lane.visibility;
    }
    EXPECT_NEAR(total / kRings, M_PI, 1e-3) << cones << " cones";
    std::printf("%2d cones, share of each band's cosine-weighted solid angle:", cones);
    for (int b = 0; b < kBands; ++b) {
      // Cosine-weighted solid angle of elevations [e0, e1]: pi (sin^2 e1 - sin^2 e0).
      const double s0 = std::sin(edges_deg[b] * M_PI / 180.0);
      const double s1 = std::sin(edges_deg[b + 1] * M_PI / 180.0);
      const double exact = M_PI * (s1 * s1 - s0 * s0);
      const double share = band_weight[b] / kRings / exact;
      std::printf(" %.4f", share);
      EXPECT_NEAR(share, 1.0, 0.02)
          << cones << " cones, band " << edges_deg[b] << "-" << edges_deg[b + 1] << " degrees";
    }
    std::printf("\n");
  }
}

// An opaque emitter (L = 1) filling one layer of voxels across the whole window, and a point
// 2.5 voxels in front of it facing it: the same irradiance whether the layer is the window's
// last one or one inside it. Cones used to stop a voxel short of the window's edge (so that the
// trilinear footprint never wrapped to the opposite face), which hid everything in the outer
// layer: a ceiling there took 40-66% of a Cornell box's indirect light with it. The window is
// 4 m wide and the point 0.16 m from the layer, which thus fills nearly all of its view
// (differential-area-to-square form factor 0.995). Cones still end at the outer layer's
// centre, half way into it: an oblique cone reads the layer partly through the volumes that
// see it edge-on, whose opacity across their travel now grows over the voxel before that centre
// (ConeAlongAWallsEdgeIsHalfBlocked) instead of saturating half a voxel early, so the outer
// layer gives 0.957 where one inside gives 0.998 (0.99 before that change).
TEST_P(ConeTraceEnergyTest, EmitterInTheWindowsOuterLayerIsSeen) {
  const bool anisotropic = GetParam();
  auto irradiance_from_layer = [&](int layer) {
    const VolumeData data = emitter_layers(
        make_clipmap_info(kR, 1, kVoxel, glm::vec3(0.3f, -0.2f, 0.1f)), layer, layer);
    VolumeGraph graph(filter_graph(kR, 1, anisotropic), &data, scene::make_builtin_scene("empty"));
    graph.render();
    const glm::vec3 corner = window_corner(data.info);
    const glm::vec3 point =
        corner + glm::vec3(float(layer - 3) + 0.5f, 0.5f * kR, 0.5f * kR) * kVoxel;
    ProbeSettings s;
    s.diffuse_cones = 16;
    s.anisotropic = anisotropic;
    const std::vector<ProbeResult> r =
        run_probes(graph, "voxel.clipmap_info", filtered_resources(anisotropic),
                   {{point, glm::vec3(1, 0, 0)}}, s);
    return r[0].irradiance.g / static_cast<float>(M_PI);
  };
  const float inside = irradiance_from_layer(kR / 2 + 8);
  const float edge = irradiance_from_layer(kR - 1);
  std::printf("%s: E/(pi L) layer inside %.4f, outer layer %.4f\n",
              anisotropic ? "anisotropic" : "isotropic", inside, edge);
  EXPECT_NEAR(inside, 0.995f, 0.05f);
  EXPECT_NEAR(edge, inside, 0.05f);
}

// A window that starts at voxel 0 (as common.voxelize places windows that stay put) is stored
// without the wrap, and cones read beyond it as empty at every mip: wide cones leaving it
// through one face see nothing of an emitter filling the opposite face's outer layers, which
// the wrap puts right beyond it, while the same cones turned round see the emitter. Measured
// 0 leaving; 0.99-1.00 turned round (anisotropic), 0.03-0.07 (isotropic).
TEST_P(ConeTraceEnergyTest, BeyondAWindowThatStaysPutIsEmpty) {
  const bool anisotropic = GetParam();
  const VolumeData data =
      emitter_layers(make_clipmap_info(kR, 1, kVoxel, glm::vec3(0.5f * kR * kVoxel)), 0, 1);
  ASSERT_EQ(glm::ivec3(data.info.levels[0].origin_voxel), glm::ivec3(0));
  VolumeGraph graph(filter_graph(kR, 1, anisotropic), &data, scene::make_builtin_scene("empty"));
  graph.render();
  const glm::vec3 corner = window_corner(data.info);
  ProbeSettings s;
  s.single_cone = true;
  s.anisotropic = anisotropic;
  for (float tan_half : {0.2f, 0.577f, 1.0f}) {
    s.tan_half_angle = tan_half;
    const glm::vec3 near_far_face = corner + glm::vec3(kR - 4.5f, 0.5f * kR, 0.5f * kR) * kVoxel;
    const std::vector<ProbeResult> r =
        run_probes(graph, "voxel.clipmap_info", filtered_resources(anisotropic),
                   {{near_far_face, glm::vec3(1, 0, 0)}, {near_far_face, glm::vec3(-1, 0, 0)}}, s);
    std::printf("%s, tan %.3f: leaving the window %.4f, turned round %.4f\n",
                anisotropic ? "anisotropic" : "isotropic", tan_half, r[0].irradiance.r,
                r[1].irradiance.r);
    EXPECT_LT(r[0].irradiance.r, 1e-4f) << "tan(half angle) " << tan_half;
    // The isotropic mips dilute the two-voxel layer over a coarse texel (OpaqueWallStopsTheCone).
    EXPECT_GT(r[1].irradiance.r, anisotropic ? 0.5f : 0.02f) << "tan(half angle) " << tan_half;
  }
}

// Semi-transparent fog (opacity 0.1 per voxel, radiance 1): the opacity a cone accumulates
// over a fixed distance must not depend on the step factor beta, because each sample's
// opacity is corrected to the step length: 1 - (1 - a)^(step / voxel).
TEST_P(ConeTraceEnergyTest, StepFactorDoesNotChangeTransmittance) {
  const bool anisotropic = GetParam();
  VolumeData data;
  fill_radiance(data, [](glm::vec3) { return glm::vec4(1.0f, 1.0f, 1.0f, 0.1f); });
  VolumeGraph graph(filter_graph(kR, 1, anisotropic), &data, scene::make_builtin_scene("empty"));
  graph.render();
  ProbeSettings s;
  s.single_cone = true;
  s.anisotropic = anisotropic;
  s.tan_half_angle = 0.01f;  // stays at the finest level
  s.max_distance = 0.5f;     // 8 voxels: expected transmittance 0.9^8
  std::vector<float> transmittance;
  for (float beta : {0.25f, 0.5f, 1.0f}) {
    s.step_factor = beta;
    const std::vector<ProbeResult> r =
        run_probes(graph, "voxel.clipmap_info", filtered_resources(anisotropic),
                   {{glm::vec3(0.0f), glm::vec3(0, 0, 1)}}, s);
    std::printf("beta %.2f: transmittance %.4f (exact %.4f)\n", beta, r[0].visibility,
                std::pow(0.9f, 8.0f));
    transmittance.push_back(r[0].visibility);
  }
  const float expected = std::pow(0.9f, 8.0f);
  for (float t : transmittance) EXPECT_NEAR(t, expected, 0.05f);
}

// A uniform emitter of radiance 1 beyond 1 m of the origin, through a three-level clipmap
// (level edges 4, 8 and 16 m, windows off-centre so the toroidal wrap and the level consistency
// of vct.filter are exercised): E / (pi L) at the origin for two normals, gathered with `s`.
std::vector<float> emitter_across_three_levels(VolumeGraph& graph, const ProbeSettings& s) {
  const std::vector<ProbeResult> r = run_probes(
      graph, "voxel.clipmap_info", filtered_resources(true),
      {{glm::vec3(0.0f), glm::vec3(0, 1, 0)}, {glm::vec3(0.0f), glm::vec3(0.6f, 0.48f, 0.64f)}}, s);
  std::vector<float> ratios;
  for (const ProbeResult& p : r) ratios.push_back(p.irradiance.g / static_cast<float>(M_PI));
  return ratios;
}

class ConeTraceThreeLevelsTest : public ConeTraceClipmapTest {
 protected:
  void SetUp() override {
    ConeTraceClipmapTest::SetUp();
    if (IsSkipped()) return;
    fill_radiance(
        data_,
        [](glm::vec3 c) {
          return glm::length(c) >= 1.0f ? glm::vec4(1.0f, 1.0f, 1.0f, 1.0f) : glm::vec4(0.0f);
        },
        3);
    graph_ = std::make_unique<VolumeGraph>(filter_graph(kR, 3, true), &data_,
                                           scene::make_builtin_scene("empty"));
    graph_->render();
  }
  VolumeData data_;
  std::unique_ptr<VolumeGraph> graph_;
};

// Cones cross from level to level and still return pi * L.
TEST_F(ConeTraceThreeLevelsTest, UniformEmitterAcrossThreeLevels) {
  for (int n : {1, 6, 16}) {
    ProbeSettings s;
    s.diffuse_cones = n;
    for (float ratio : emitter_across_three_levels(*graph_, s)) {
      std::printf("3 levels, N=%2d: E/(pi L) = %.4f\n", n, ratio);
      EXPECT_NEAR(ratio, 1.0f, 0.05f) << "N = " << n;
    }
  }
}

// The same with much work per gather: 32 cones of eight lanes at half steps. llvmpipe ends every
// loop of an invocation once all of them together have run 65535 iterations; the tracer's
// per-sample searches over levels and mips were loops, so such a gather lost its last cones
// there (a 128^3 clipmap was 16% darker with 32 cones than with 16; docs/error-budget.md,
// twenty-third round). Since lanes read voxels of their share of the cone's width (thirtieth
// round) they take more steps, and at a quarter step 32 cones reach the limit on llvmpipe
// (0.81 of pi * L there; 16 cones at a quarter step and 32 at half steps stay within it). On
// any device this must give pi * L.
TEST_F(ConeTraceThreeLevelsTest, ManyNarrowStepsKeepEveryCone) {
  ProbeSettings s;
  s.diffuse_cones = 32;
  s.lanes = 8;
  s.step_factor = 0.5f;
  for (float ratio : emitter_across_three_levels(*graph_, s)) {
    std::printf("3 levels, 32 cones x 8 lanes, step 0.5: E/(pi L) = %.4f\n", ratio);
    EXPECT_NEAR(ratio, 1.0f, 0.05f);
  }
}

INSTANTIATE_TEST_SUITE_P(Modes, ConeTraceEnergyTest, ::testing::Values(false, true),
                         [](const auto& mode) { return mode.param ? "anisotropic" : "isotropic"; });

}  // namespace
}  // namespace voxgi::test
