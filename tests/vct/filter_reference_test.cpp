// vct.filter against a CPU reference on a random 16^3 clipmap with two levels (so the level
// consistency rule is exercised too), in both modes and anisotropic with random faces (and
// random light shares), every mip of every volume. Random values include NaN, Inf and out-of-range
// opacity, which the filter must scrub to zero.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include <glm/gtc/packing.hpp>

#include "engine/scene/builtin_scenes.hpp"
#include "tests/gpu/gpu_test_env.hpp"
#include "tests/vct/filter_graphs.hpp"
#include "tests/vct/volume_harness.hpp"

namespace voxgi::test {
namespace {

constexpr int kR = 16;
constexpr int kLevels = 2;

glm::vec4 scrub(glm::vec4 v) {
  glm::vec4 out;
  for (int c = 0; c < 3; ++c) out[c] = std::isfinite(v[c]) ? glm::clamp(v[c], 0.0f, 65504.0f) : 0;
  out.a = std::isfinite(v.a) ? glm::clamp(v.a, 0.0f, 1.0f) : 0.0f;
  return out;
}

glm::vec4 over(glm::vec4 front, glm::vec4 back) {
  return {glm::vec3(front) + (1.0f - front.a) * glm::vec3(back),
          front.a + (1.0f - front.a) * back.a};
}

// Children ordered x fastest; volume 2k+s looks along axis k, s = 0 positive.
glm::vec4 filter_children(const glm::vec4 c[8], int volume, bool anisotropic) {
  glm::vec4 sum(0.0f);
  if (!anisotropic) {
    for (int i = 0; i < 8; ++i) sum += c[i];
    return sum / 8.0f;
  }
  const int stride = 1 << (volume / 2);
  const bool positive = volume % 2 == 0;
  for (int i = 0; i < 8; ++i) {
    if (i & stride) continue;
    sum += positive ? over(c[i], c[i + stride]) : over(c[i + stride], c[i]);
  }
  return sum / 4.0f;
}

// Premultiplied radiance and opacity from the filter's stored form
// (shaders/contracts/vct_volume_encoding.glsl: the same, opacity clamped to [0, 1]).
glm::vec4 decode_filtered(glm::vec4 stored) {
  const float a = std::clamp(stored.a, 0.0f, 1.0f);
  if (!(a > 0.0f)) return glm::vec4(0.0f);
  return glm::vec4(glm::max(glm::vec3(stored), glm::vec3(0.0f)), a);
}

// volumes[v][mip]: texels of the whole stacked image at that mip.
using Reference = std::vector<std::vector<std::vector<glm::vec4>>>;

// How bright a voxel holding its own light looks to cones travelling along volume v, relative
// to its mean radiance (shaders/vct/filter.comp, directional_light), for axis-aligned groups
// (faces_texel): group v ^ 1 faces the cone, group v faces away, the others are seen edge-on;
// the footprint is max(towards, away) + edge, and what shows is the light of the groups facing
// the cone or seen edge-on. `lit`: the light shares' bits (0: the area shares stand in).
float directional_light(const glm::vec4& faces_bits, uint32_t lit, int volume) {
  const uint32_t area_bits = glm::floatBitsToUint(faces_bits.w);
  float area = 0.0f, light = 0.0f;
  for (int g = 0; g < 6; ++g) {
    area += float((area_bits >> (5 * g)) & 31u);
    light += float((lit >> (5 * g)) & 31u);
  }
  if (area == 0.0f) return 1.0f;
  float towards = 0.0f, away = 0.0f, edge = 0.0f, shown = 0.0f;
  for (int g = 0; g < 6; ++g) {
    const float s = float((area_bits >> (5 * g)) & 31u) / area;
    if (s <= 0.0f) continue;
    const float l = light > 0.0f ? float((lit >> (5 * g)) & 31u) / light : s;
    if (g / 2 != volume / 2) {
      edge += s;
      shown += l;
    } else if (g != volume) {  // the group's normal points against the cone's travel
      towards += s;
      shown += l;
    } else {
      away += s;
    }
  }
  const float footprint = std::max(towards, away) + edge;
  return footprint > 1e-6f ? shown / footprint : 0.0f;
}

// `faces`: the voxels' faces (nullptr: the filter has none); `light_shares`: their light
// shares (nullptr: none).
Reference reference_filter(const ClipmapInfo& info, const CpuClipmap& radiance, bool anisotropic,
                           const CpuClipmap* faces = nullptr,
                           const CpuClipmap* light_shares = nullptr) {
  const int volumes = anisotropic ? 6 : 1;
  int mips = 0;
  while ((kR >> mips) > 0) ++mips;
  Reference ref(volumes, std::vector<std::vector<glm::vec4>>(mips));
  for (int v = 0; v < volumes; ++v) {
    for (int m = 0; m < mips; ++m) {
      const size_t rm = size_t(kR >> m);
      ref[v][m].assign(rm * rm * rm * kLevels, glm::vec4(0.0f));
    }
  }
  auto idx = [](glm::ivec3 t, int rm) { return (size_t(t.z) * rm + t.y) * rm + t.x; };
  for (int level = 0; level < kLevels; ++level) {
    for (int z = 0; z < kR; ++z) {
      for (int y = 0; y < kR; ++y) {
        for (int x = 0; x < kR; ++x) {
          const glm::ivec3 window(x, y, z);
          const glm::ivec3 texel = clipmap_texel(info, window, level);
          bool from_finer = false;
          glm::ivec3 first(0);
          if (level > 0) {
            const glm::ivec3 world = window + glm::ivec3(info.levels[level].origin_voxel);
            first = world * 2 - glm::ivec3(info.levels[level - 1].origin_voxel);
            from_finer = glm::all(glm::greaterThanEqual(first, glm::ivec3(0))) &&
                         glm::all(glm::lessThan(first + 1, glm::ivec3(kR)));
          }
          for (int v = 0; v < volumes; ++v) {
            glm::vec4 value;
            if (from_finer) {
              glm::vec4 c[8];
              for (int i = 0; i < 8; ++i) {
                const glm::ivec3 o(i & 1, (i >> 1) & 1, (i >> 2) & 1);
                const glm::ivec3 t = clipmap_texel(info, first + o, level - 1);
                c[i] = ref[v][0][idx(t, kR)];
              }
              value = filter_children(c, v, anisotropic);
            } else {
              const glm::vec4 r = scrub(radiance.at(texel));
              glm::vec3 rgb(r);
              if (faces && anisotropic && glm::any(glm::greaterThan(rgb, glm::vec3(0.0f)))) {
                const uint32_t lit =
                    light_shares ? glm::floatBitsToUint(light_shares->at(texel).x) : 0u;
                rgb *= directional_light(faces->at(texel), lit, v);
              }
              value = glm::vec4(rgb * r.a, r.a);
            }
            ref[v][0][idx(texel, kR)] = scrub(value);
          }
        }
      }
    }
  }
  for (int m = 1; m < mips; ++m) {
    const int rm = kR >> m;
    const int rs = rm * 2;
    for (int z = 0; z < rm * kLevels; ++z) {
      for (int y = 0; y < rm; ++y) {
        for (int x = 0; x < rm; ++x) {
          const int level = z / rm;
          const glm::ivec3 local(x, y, z - level * rm);
          for (int v = 0; v < volumes; ++v) {
            glm::vec4 c[8];
            for (int i = 0; i < 8; ++i) {
              glm::ivec3 t = local * 2 + glm::ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
              t.z += level * rs;
              c[i] = ref[v][m - 1][idx(t, rs)];
            }
            ref[v][m][idx({x, y, z}, rm)] = scrub(filter_children(c, v, anisotropic));
          }
        }
      }
    }
  }
  return ref;
}

enum class FilterMode { Isotropic, Anisotropic, AnisotropicWithFaces, AnisotropicWithLightShares };

class FilterReferenceTest : public GpuTest, public ::testing::WithParamInterface<FilterMode> {};

TEST_P(FilterReferenceTest, MatchesCpuReferenceOnEveryMip) {
  const bool anisotropic = GetParam() != FilterMode::Isotropic;
  const bool with_shares = GetParam() == FilterMode::AnisotropicWithLightShares;
  const bool with_faces = GetParam() == FilterMode::AnisotropicWithFaces || with_shares;
  VolumeData data;
  // Windows offset from the origin so that the toroidal wrap is not the identity.
  data.info = make_clipmap_info(kR, kLevels, 0.25f, glm::vec3(1.3f, -0.7f, 2.9f));
  std::mt19937 rng(1234);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  CpuClipmap radiance(kR, kLevels);
  for (glm::vec4& t : radiance.texels) {
    const float roll = unit(rng);
    if (roll < 0.4f) {
      t = glm::vec4(0.0f);
    } else {
      t = glm::vec4(4.0f * unit(rng), 4.0f * unit(rng), 4.0f * unit(rng), unit(rng));
      if (roll > 0.98f) t.r = std::numeric_limits<float>::quiet_NaN();
      if (roll > 0.96f && roll <= 0.98f) t.g = std::numeric_limits<float>::infinity();
      if (roll > 0.94f && roll <= 0.96f) t.a = 3.0f;  // opacity out of range
    }
    // Round to half precision as the GPU stores it.
    for (int c = 0; c < 4; ++c) {
      if (std::isfinite(t[c]) && t[c] < 65504.0f) {
        t[c] = glm::unpackHalf1x16(glm::packHalf1x16(t[c]));
      }
    }
  }
  data.volumes["radiance"] = radiance;
  // Random groups with random area shares; a third of the voxels have none (one plane).
  CpuClipmap faces(kR, kLevels);
  for (glm::vec4& t : faces.texels) {
    std::vector<std::pair<int, uint32_t>> groups;
    for (int g = 0; g < 6; ++g) {
      if (unit(rng) < 0.3f) groups.push_back({g, 1u + uint32_t(unit(rng) * 30.99f)});
    }
    if (unit(rng) < 0.33f) groups.clear();
    t = faces_texel(groups);
  }
  // Random light shares over each voxel's groups (a tenth none: the area shares stand in).
  CpuClipmap shares(kR, kLevels);
  for (size_t i = 0; i < shares.texels.size(); ++i) {
    const uint32_t area_bits = glm::floatBitsToUint(faces.texels[i].w);
    uint32_t bits = 0u;
    for (int g = 0; g < 6; ++g) {
      if (((area_bits >> (5 * g)) & 31u) != 0u && unit(rng) < 0.7f) {
        bits |= uint32_t(unit(rng) * 31.99f) << (5 * g);
      }
    }
    if (unit(rng) < 0.1f) bits = 0u;
    shares.texels[i] = glm::vec4(glm::uintBitsToFloat(bits), 0.0f, 0.0f, 0.0f);
  }
  if (with_faces) data.volumes["faces"] = faces;
  if (with_shares) data.volumes["light_shares"] = shares;
  VolumeGraph graph(filter_graph(kR, kLevels, anisotropic, false, with_faces, with_shares), &data,
                    scene::make_builtin_scene("empty"));
  graph.render();
  const Reference ref =
      reference_filter(data.info, radiance, anisotropic, with_faces ? &faces : nullptr,
                       with_shares ? &shares : nullptr);
  const std::vector<std::string> names = filtered_resources(anisotropic);
  for (size_t v = 0; v < names.size(); ++v) {
    for (size_t m = 0; m < ref[v].size(); ++m) {
      const std::vector<glm::vec4> gpu = graph.download(names[v], static_cast<uint32_t>(m));
      ASSERT_EQ(gpu.size(), ref[v][m].size()) << names[v] << " mip " << m;
      float worst = 0.0f;
      size_t bad = 0;
      for (size_t i = 0; i < gpu.size(); ++i) {
        for (int c = 0; c < 4; ++c) {
          const float g = decode_filtered(gpu[i])[c];
          const float r = ref[v][m][i][c];
          // Half precision: 11-bit mantissa, plus rounding at every mip of the chain; an opaque
          // voxel is stored with opacity 1 - e^-8.
          const float tolerance = 2e-3f + 4e-3f * std::abs(r);
          if (!std::isfinite(g) || std::abs(g - r) > tolerance) ++bad;
          worst = std::max(worst, std::abs(g - r));
        }
      }
      EXPECT_EQ(bad, 0u) << names[v] << " mip " << m << " worst difference " << worst;
      if (m == 0 || m + 1 == ref[v].size()) {
        std::printf("%s mip %zu: worst |gpu - cpu| = %.2e\n", names[v].c_str(), m, worst);
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Modes, FilterReferenceTest,
                         ::testing::Values(FilterMode::Isotropic, FilterMode::Anisotropic,
                                           FilterMode::AnisotropicWithFaces,
                                           FilterMode::AnisotropicWithLightShares),
                         [](const auto& mode) {
                           switch (mode.param) {
                             case FilterMode::Isotropic:
                               return "isotropic";
                             case FilterMode::Anisotropic:
                               return "anisotropic";
                             case FilterMode::AnisotropicWithLightShares:
                               return "anisotropic_with_light_shares";
                             default:
                               return "anisotropic_with_faces";
                           }
                         });

}  // namespace
}  // namespace voxgi::test

namespace voxgi::test {
namespace {

class FilterBehaviourTest : public GpuTest {};

// The filter runs only when the radiance volume (or the clipmap info) was rewritten.
TEST_F(FilterBehaviourTest, SkipsWhileTheRadianceIsUnchanged) {
  VolumeData data;
  data.info = make_clipmap_info(kR, 1, 0.25f, glm::vec3(0.0f));
  data.volumes["radiance"] = CpuClipmap(kR, 1);
  VolumeGraph graph(filter_graph(kR, 1, true), &data, scene::make_builtin_scene("empty"));
  graph.render();
  EXPECT_EQ(graph.skipped("filter"), "");
  graph.render();
  EXPECT_EQ(graph.skipped("filter"), "radiance volume unchanged");
  ++data.version;
  graph.render();
  EXPECT_EQ(graph.skipped("filter"), "");
}

// A coarser level's voxels that no finer level covers are voxelized at their own size, so a
// surface there is one coarse voxel thick, while next to them, where the finer level covers,
// the filter makes the same surface one fine voxel thick: opaque across it, half covered along
// it one level up (half of the voxel, isotropic). Given the voxel normals, the filter gives the
// directly voxelized voxels what it would have given them from the finer level, so the two
// halves of one floor agree (they did not: opaque on one side, half on the other; the default
// clipmap's same-bounce relMSE on the Cornell boxes fell from 0.46 / 0.54 to 0.16 / 0.17 at
// 32^3 and from 0.028 / 0.027 to 0.015 / 0.013 at 128^3 with 16 cones, docs/error-budget.md,
// sixth round).
TEST_F(FilterBehaviourTest, CoarseLevelFloorAgreesWithItsFilteredTwin) {
  constexpr int kLevelsHere = 2;
  VolumeData data;
  // Level 0 covers world voxels -8..7, level 1 (twice the size) -8..7 of its own: level 0
  // covers level 1's window voxels 4..11 along x and y.
  data.info = make_clipmap_info(kR, kLevelsHere, 0.25f, glm::vec3(0.0f));
  CpuClipmap radiance(kR, kLevelsHere);
  CpuClipmap normal(kR, kLevelsHere);
  const glm::vec4 lit_floor(0.5f, 1.0f, 2.0f, 1.0f);
  const glm::vec4 up(0.0f, 0.0f, 1.0f, 1.0f);  // occupied, the plane through the centre
  // The floor: world layer z = 0 at both levels (level 1's layer 0 has level 0's layers 0 and
  // 1 as children, the floor in the lower one).
  for (int level = 0; level < kLevelsHere; ++level) {
    for (int y = 0; y < kR; ++y) {
      for (int x = 0; x < kR; ++x) {
        const glm::ivec3 texel = clipmap_texel(data.info, {x, y, kR / 2}, level);
        radiance.at(texel) = lit_floor;
        normal.at(texel) = up;
      }
    }
  }
  // A voxel whose writers' normals cancelled (both faces of a thin wall) stays opaque from
  // every side.
  const glm::ivec3 thin_wall = clipmap_texel(data.info, {1, 1, 2}, 1);
  radiance.at(thin_wall) = lit_floor;
  normal.at(thin_wall) = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  data.volumes["radiance"] = radiance;
  data.volumes["normal"] = normal;
  auto at = [&](const std::vector<glm::vec4>& texels, glm::ivec3 texel) {
    return decode_filtered(texels[(size_t(texel.z) * kR + texel.y) * kR + texel.x]);
  };
  for (bool anisotropic : {true, false}) {
    VolumeGraph graph(filter_graph(kR, kLevelsHere, anisotropic, true), &data,
                      scene::make_builtin_scene("empty"));
    graph.render();
    const std::vector<std::string> volumes = filtered_resources(anisotropic);
    for (size_t v = 0; v < volumes.size(); ++v) {
      const std::vector<glm::vec4> texels = graph.download(volumes[v]);
      const bool across = anisotropic && v >= 4;
      const float expected_opacity = across ? 1.0f : 0.5f;
      const glm::vec4 filtered = at(texels, clipmap_texel(data.info, {8, 8, kR / 2}, 1));
      const glm::vec4 injected = at(texels, clipmap_texel(data.info, {1, 8, kR / 2}, 1));
      std::printf("[levels] %s: floor opacity %.4f where level 0 covers, %.4f where it does not\n",
                  volumes[v].c_str(), filtered.a, injected.a);
      EXPECT_NEAR(filtered.a, expected_opacity, 2e-3f) << volumes[v];
      EXPECT_NEAR(injected.a, filtered.a, 2e-3f) << volumes[v];
      for (int c = 0; c < 3; ++c) {
        // Premultiplied: the radiance per unit of opacity is the floor's on both sides.
        EXPECT_NEAR(injected[c], lit_floor[c] * injected.a, 4e-3f * lit_floor[c]) << volumes[v];
        EXPECT_NEAR(injected[c], filtered[c], 4e-3f * lit_floor[c]) << volumes[v];
      }
      EXPECT_GT(at(texels, thin_wall).a, 0.999f) << volumes[v] << ": the cancelled normal";
    }
  }
}

// A voxel that holds both faces of a thin wall, lit on one of them: its mean radiance averages
// the lit face with the dark one, so the filter must send the lit face's light (twice the
// mean) towards the lit side and none through the wall. Before the light shares it sent a
// quarter of the lit face's light each way (the mean, halved by the facing), darkening the
// lit side and leaking to the dark one (docs/error-budget.md, nineteenth round).
TEST_F(FilterBehaviourTest, ThinWallSendsItsLitFaceLightOnlyItsWay) {
  VolumeData data;
  data.info = make_clipmap_info(kR, 1, 0.25f, glm::vec3(0.0f));
  CpuClipmap radiance(kR, 1), faces(kR, 1), shares(kR, 1);
  const glm::ivec3 wall = clipmap_texel(data.info, {5, 6, 7}, 0);
  const float mean = 0.5f;  // the lit face's radiance 1, the dark face's 0, nearly half each
  radiance.at(wall) = glm::vec4(mean, mean, mean, 1.0f);
  faces.at(wall) = faces_texel({{0, 15}, {1, 16}});  // +X (dark) 15/31, -X (lit) 16/31
  shares.at(wall) = glm::vec4(glm::uintBitsToFloat(31u << 5), 0.0f, 0.0f, 0.0f);  // all -X
  data.volumes["radiance"] = radiance;
  data.volumes["faces"] = faces;
  data.volumes["light_shares"] = shares;
  VolumeGraph graph(filter_graph(kR, 1, true, false, true, true), &data,
                    scene::make_builtin_scene("empty"));
  graph.render();
  // Seen from -x (cones travelling +x) the lit face fills the voxel's footprint; from +x the
  // dark face does; seen edge-on (y, z) the voxel shows its mean.
  const float lit = mean * 31.0f / 16.0f;
  const float expected[6] = {lit, 0.0f, mean, mean, mean, mean};
  const std::vector<std::string> volumes = filtered_resources(true);
  for (size_t v = 0; v < volumes.size(); ++v) {
    const glm::vec4 texel =
        decode_filtered(graph.download(volumes[v])[(size_t(wall.z) * kR + wall.y) * kR + wall.x]);
    std::printf("[thin wall] %s: %.4f (expected %.4f)\n", volumes[v].c_str(), texel.r, expected[v]);
    EXPECT_NEAR(texel.r, expected[v], 2e-3f) << volumes[v];
    EXPECT_GT(texel.a, 0.999f) << volumes[v];
  }
}

// A mode whose outputs are not bound is a compile error naming the pass, the field and where
// the mode was set.
TEST_F(FilterBehaviourTest, ModeWithoutItsOutputsNamesTheField) {
  VolumeData data;
  data.info = make_clipmap_info(kR, 1, 0.25f, glm::vec3(0.0f));
  data.volumes["radiance"] = CpuClipmap(kR, 1);
  try {
    VolumeGraph graph(filter_graph(kR, 1, false), &data, scene::make_builtin_scene("empty"), 64, 64,
                      {{"filter.mode", "anisotropic"}});
    FAIL() << "expected an error";
  } catch (const std::exception& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("--set filter.mode=anisotropic: error: pass 'filter' field "
                           "'params.mode'"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("pos_x"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace voxgi::test
