// The contracts between pass families (passes/contracts, shaders/contracts): every GLSL twin
// compiles on its own, and data written by the C++ side reads back field for field through the
// GLSL declarations on the device, so a field added, moved or resized on one side only fails
// here rather than as wrong light somewhere downstream.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/shader_compiler.hpp"
#include "passes/contracts/shadow_data.hpp"
#include "passes/contracts/voxel_clipmap.hpp"
#include "tests/gpu/buffer_probe.hpp"
#include "tests/gpu/gpu_test_env.hpp"
#include "tests/gpu/shader_files.hpp"

namespace voxgi::test {
namespace {

namespace fs = std::filesystem;

const fs::path kShaders = fs::path(VOXGI_SOURCE_DIR) / "shaders";
const fs::path kProbes = fs::path(VOXGI_SOURCE_DIR) / "tests" / "contracts" / "shaders";

class ContractsTest : public GpuTest {
 protected:
  gpu::ShaderCompiler compiler_{{kProbes, kShaders}, ""};

  gpu::Buffer storage(VkDeviceSize bytes, const char* name) {
    return gpu::Buffer(context(), bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                       gpu::MemoryUsage::GpuOnly, name);
  }

  void run_probe(const char* probe, gpu::Buffer& input, gpu::Buffer& output, uint32_t count) {
    run_buffer_probe(compiler_, probe, input, output, count);
  }
};

TEST_F(ContractsTest, EveryGlslContractCompilesOnItsOwn) {
  const fs::path dir = make_temp_dir("voxgi-contracts");
  gpu::ShaderCompiler compiler({dir, kShaders}, "");
  std::vector<fs::path> contracts;
  for (const auto& entry : fs::directory_iterator(kShaders / "contracts")) {
    if (entry.path().extension() == ".glsl") contracts.push_back(entry.path().filename());
  }
  std::sort(contracts.begin(), contracts.end());
  ASSERT_GE(contracts.size(), 4u);
  for (const fs::path& contract : contracts) {
    SCOPED_TRACE(contract.string());
    // The clipmap description first: readers of clipmap data include it before their contract.
    const std::string source =
        "#version 460\n#extension GL_GOOGLE_include_directive : require\n"
        "#include \"contracts/voxel_clipmap.glsl\"\n"
        "#include \"contracts/" +
        contract.string() +
        "\"\n"
        "layout(local_size_x = 1) in;\nvoid main() {}\n";
    const std::string name = contract.stem().string() + ".comp";
    write_file(dir / name, source);
    EXPECT_NO_THROW(compiler.compile({name}));
  }
}

TEST_F(ContractsTest, ShadowLightReadsBackFieldForFieldInGlsl) {
  constexpr uint32_t kLights = 3;
  std::vector<contracts::ShadowLight> lights(kLights);
  float next = 1.0f;
  for (contracts::ShadowLight& light : lights) {
    for (glm::mat4& m : light.view_proj) {
      for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) m[c][r] = next++;
      }
    }
    light.origin = {next, next + 1, next + 2, next + 3};
    light.info = {next + 4, next + 5, next + 6, next + 7};
    next += 8;
  }
  const uint32_t fields_per_light = contracts::kShadowFacesPerLight * 16 + 8;
  gpu::Buffer input = storage(kLights * contracts::kShadowLightBytes, "test.shadow_lights");
  gpu::Buffer output = storage(kLights * fields_per_light * sizeof(float), "test.shadow_fields");
  input.upload_vector(lights);
  run_probe("shadow_data_probe.comp", input, output, kLights);

  const std::vector<float> fields = output.download_vector<float>();
  size_t o = 0;
  for (uint32_t l = 0; l < kLights; ++l) {
    for (uint32_t face = 0; face < contracts::kShadowFacesPerLight; ++face) {
      for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
          ASSERT_EQ(fields[o++], lights[l].view_proj[face][c][r])
              << "light " << l << " view_proj[" << face << "][" << c << "][" << r << "]";
        }
      }
    }
    for (int i = 0; i < 4; ++i) ASSERT_EQ(fields[o++], lights[l].origin[i]) << "origin " << i;
    for (int i = 0; i < 4; ++i) ASSERT_EQ(fields[o++], lights[l].info[i]) << "info " << i;
  }
}

TEST_F(ContractsTest, VoxelClipmapInfoReadsBackFieldForFieldInGlsl) {
  contracts::VoxelClipmapInfo info{};
  info.anchor = {1.5f, -2.25f, 3.125f, 4.0f};
  info.dims = {64u, 5u, 7u, 9u};
  for (uint32_t l = 0; l < contracts::kVoxelMaxLevels; ++l) {
    const int base = 10 * static_cast<int>(l);
    info.levels[l].origin_voxel = {base - 3, base + 1, -base - 2, static_cast<int>(l % 2)};
    info.levels[l].min_corner_size = {0.5f * float(l), -0.25f * float(l), float(l) + 0.75f,
                                      0.125f * float(1u << l)};
  }
  gpu::Buffer input = storage(contracts::kVoxelClipmapInfoBytes, "test.clipmap_info");
  const uint32_t fields_count = 8 + contracts::kVoxelMaxLevels * 8;
  gpu::Buffer output = storage(fields_count * sizeof(float), "test.clipmap_fields");
  input.upload(&info, sizeof(info));
  run_probe("voxel_clipmap_probe.comp", input, output, 0);

  const std::vector<float> fields = output.download_vector<float>();
  size_t o = 0;
  for (int i = 0; i < 4; ++i) EXPECT_EQ(fields[o++], info.anchor[i]) << "anchor " << i;
  for (int i = 0; i < 4; ++i) EXPECT_EQ(fields[o++], float(info.dims[i])) << "dims " << i;
  for (uint32_t l = 0; l < contracts::kVoxelMaxLevels; ++l) {
    const contracts::VoxelClipmapLevelInfo& level = info.levels[l];
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(fields[o++], float(level.origin_voxel[i])) << "level " << l << " origin " << i;
    }
    EXPECT_EQ(fields[o++], level.origin_voxel.w != 0 ? 1.0f : 0.0f) << "level " << l << " valid";
    for (int i = 0; i < 4; ++i) {
      EXPECT_EQ(fields[o++], level.min_corner_size[i]) << "level " << l << " min/size " << i;
    }
  }
}

TEST_F(ContractsTest, GbufferReadersDecodeWhatTheWriterEncodes) {
  struct Surface {
    glm::vec4 base_color_metallic;
    glm::vec4 normal_roughness;
    glm::vec4 emission_occlusion;
  };
  const std::vector<Surface> surfaces = {
      {{0.25f, 0.5f, 0.75f, 0.0f}, {0.0f, 1.0f, 0.0f, 0.5f}, {0.0f, 0.0f, 0.0f, 1.0f}},
      {{1.0f, 0.0f, 0.125f, 1.0f}, {0.6f, 0.0f, -0.8f, 0.03f}, {3.0f, 20.0f, 0.5f, 0.25f}},
  };
  const uint32_t count = static_cast<uint32_t>(surfaces.size());
  gpu::Buffer input = storage(count * sizeof(Surface), "test.gbuffer_surfaces");
  gpu::Buffer output = storage(count * 4 * sizeof(glm::vec4), "test.gbuffer_decoded");
  input.upload_vector(surfaces);
  run_probe("gbuffer_probe.comp", input, output, count);

  const std::vector<glm::vec4> decoded = output.download_vector<glm::vec4>();
  for (uint32_t i = 0; i < count; ++i) {
    SCOPED_TRACE("surface " + std::to_string(i));
    const Surface& s = surfaces[i];
    const glm::vec4* d = &decoded[4 * i];
    for (int c = 0; c < 4; ++c) {
      EXPECT_FLOAT_EQ(d[0][c], s.base_color_metallic[c]) << "base colour, metallic " << c;
      EXPECT_NEAR(d[1][c], s.normal_roughness[c], 1e-6f) << "normal, roughness " << c;
      EXPECT_FLOAT_EQ(d[2][c], s.emission_occlusion[c]) << "emission, occlusion " << c;
    }
    EXPECT_FLOAT_EQ(d[3].x, s.normal_roughness.w) << "roughness in the material target";
    EXPECT_FLOAT_EQ(d[3].y, s.emission_occlusion.w) << "occlusion in the base-colour target";
    EXPECT_FLOAT_EQ(d[3].z, 1.0f) << "coverage";
    EXPECT_FLOAT_EQ(d[3].w, 1.0f) << "depth 0.5 holds a surface, the cleared depth 1 none";
  }
}

TEST_F(ContractsTest, VoxelPlaneOffsetReadsBackAsWritten) {
  const std::vector<float> offsets = {-1.0f, -0.5f, 0.0f, 0.25f, 1.0f, 3.0f};
  const uint32_t count = static_cast<uint32_t>(offsets.size());
  gpu::Buffer input = storage(count * sizeof(float), "test.plane_offsets");
  gpu::Buffer output = storage(count * sizeof(glm::vec2), "test.plane_decoded");
  input.upload_vector(offsets);
  run_probe("voxel_volumes_probe.comp", input, output, count);

  const std::vector<glm::vec2> decoded = output.download_vector<glm::vec2>();
  for (uint32_t i = 0; i < count; ++i) {
    // |d| <= 1 by the contract: larger offsets come back clamped.
    EXPECT_NEAR(decoded[i].x, std::clamp(offsets[i], -1.0f, 1.0f), 1e-6f) << "offset " << i;
    EXPECT_EQ(decoded[i].y, 1.0f) << "an encoded voxel reads as occupied, offset " << i;
  }
}

}  // namespace
}  // namespace voxgi::test
