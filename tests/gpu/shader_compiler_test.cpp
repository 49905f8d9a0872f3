#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/gpu/shader_compiler.hpp"
#include "tests/gpu/gpu_test_env.hpp"
#include "tests/gpu/shader_files.hpp"

namespace voxgi::test {
namespace {

namespace fs = std::filesystem;
using ShaderCompilerTest = GpuTest;

// A compute shader writing VALUE (a define) plus what its includes return into a buffer.
const char* kValueShader = R"(#version 460
#include "lib/offset.glsl"
layout(local_size_x = 1) in;
layout(set = 0, binding = 0, std430) buffer Output { float result; };
void main() { result = float(VALUE) + offset(); }
)";

float run_value_shader(gpu::Context& context, const std::vector<uint32_t>& spirv) {
  gpu::PipelineLayoutDesc layout;
  layout.bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}};
  gpu::ComputePipeline pipeline(context, spirv, layout, "test.value");
  gpu::Buffer out(context, sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                  gpu::MemoryUsage::GpuOnly, "test.value_out");
  context.immediate_submit([&](VkCommandBuffer cmd) {
    pipeline.bind(cmd);
    gpu::DescriptorWriter().storage_buffer(0, out).push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE,
                                                        pipeline.layout());
    vkCmdDispatch(cmd, 1, 1, 1);
  });
  return out.download_vector<float>()[0];
}

std::string compile_error(gpu::ShaderCompiler& compiler, const gpu::ShaderRequest& request) {
  try {
    compiler.compile(request);
  } catch (const gpu::ShaderError& error) {
    return error.what();
  }
  return "";
}

TEST_F(ShaderCompilerTest, ErrorNamesFileAndLine) {
  auto root = make_temp_dir("voxgi-shaders");
  write_file(root / "broken.comp",
             "#version 460\nlayout(local_size_x = 1) in;\n\n"
             "void main() { undefined_thing = 1; }\n");
  gpu::ShaderCompiler compiler({root}, "");
  std::string message = compile_error(compiler, {"broken.comp"});
  ASSERT_FALSE(message.empty());
  EXPECT_NE(message.find("broken.comp:4: error:"), std::string::npos) << message;
  EXPECT_NE(message.find("undefined_thing"), std::string::npos) << message;
}

TEST_F(ShaderCompilerTest, ErrorInIncludedFileNamesTheIncludedFile) {
  auto root = make_temp_dir("voxgi-shaders");
  write_file(root / "lib" / "bad.glsl", "// a helper\nfloat helper() {\n  return nope;\n}\n");
  write_file(root / "main.comp",
             "#version 460\n#include \"lib/bad.glsl\"\nlayout(local_size_x = 1) in;\n"
             "void main() { helper(); }\n");
  gpu::ShaderCompiler compiler({root}, "");
  std::string message = compile_error(compiler, {"main.comp"});
  ASSERT_FALSE(message.empty());
  EXPECT_NE(message.find("bad.glsl:3: error:"), std::string::npos) << message;
  EXPECT_NE(message.find("included from"), std::string::npos) << message;
  EXPECT_NE(message.find("main.comp"), std::string::npos) << message;
}

TEST_F(ShaderCompilerTest, MissingIncludeAndMissingFileAreReported) {
  auto root = make_temp_dir("voxgi-shaders");
  write_file(root / "main.comp",
             "#version 460\n\n#include \"lib/absent.glsl\"\nlayout(local_size_x = 1) in;\n"
             "void main() {}\n");
  gpu::ShaderCompiler compiler({root}, "");
  std::string message = compile_error(compiler, {"main.comp"});
  EXPECT_NE(message.find("main.comp:3: error:"), std::string::npos) << message;
  EXPECT_NE(message.find("lib/absent.glsl"), std::string::npos) << message;
  try {
    compiler.compile({"nowhere.comp"});
    FAIL() << "expected gpu::Error";
  } catch (const gpu::Error& error) {
    EXPECT_NE(std::string(error.what()).find("nowhere.comp"), std::string::npos);
  }
  write_file(root / "shader.txt", "#version 460\nvoid main() {}\n");
  EXPECT_THROW(compiler.compile({"shader.txt"}), gpu::Error);
  EXPECT_NO_THROW(compiler.compile({"shader.txt", VK_SHADER_STAGE_COMPUTE_BIT}));
}

TEST_F(ShaderCompilerTest, IncludesResolveRelativeToIncluderThenRoots) {
  auto root = make_temp_dir("voxgi-shaders");
  // main.comp (in sub/) finds lib/offset.glsl through the root; offset.glsl finds its
  // neighbour scale.glsl relative to itself; scale.glsl pulls common/base.glsl from the root.
  write_file(root / "sub" / "main.comp", kValueShader);
  write_file(root / "lib" / "offset.glsl",
             "#include \"scale.glsl\"\nfloat offset() { return 0.25 * scale(); }\n");
  write_file(root / "lib" / "scale.glsl",
             "#include <common/base.glsl>\nfloat scale() { return BASE; }\n");
  write_file(root / "common" / "base.glsl", "#define BASE 2.0\n");
  gpu::ShaderCompiler compiler({root}, "");
  auto spirv = compiler.compile({"sub/main.comp", {}, {{"VALUE", "3"}}});
  EXPECT_FLOAT_EQ(run_value_shader(context(), spirv), 3.5f);
}

TEST_F(ShaderCompilerTest, DefinesChangeTheResult) {
  auto root = make_temp_dir("voxgi-shaders");
  write_file(root / "main.comp", kValueShader);
  write_file(root / "lib" / "offset.glsl", "float offset() { return 0.0; }\n");
  gpu::ShaderCompiler compiler({root}, make_temp_dir("voxgi-cache"));
  auto three = compiler.compile({"main.comp", {}, {{"VALUE", "3"}}});
  auto seven = compiler.compile({"main.comp", {}, {{"VALUE", "7"}}});
  auto flag = compiler.compile({"main.comp", {}, {{"VALUE", ""}}});
  EXPECT_FLOAT_EQ(run_value_shader(context(), three), 3.0f);
  EXPECT_FLOAT_EQ(run_value_shader(context(), seven), 7.0f);
  EXPECT_FLOAT_EQ(run_value_shader(context(), flag), 1.0f);
  EXPECT_EQ(compiler.stats().compiled, 3u);
  EXPECT_THROW(compiler.compile({"main.comp", {}, {{"BAD NAME", "1"}}}), gpu::Error);
}

TEST_F(ShaderCompilerTest, DiskCacheIsHitAndCorruptEntriesAreRecompiled) {
  auto root = make_temp_dir("voxgi-shaders");
  auto cache = make_temp_dir("voxgi-cache");
  write_file(root / "main.comp", kValueShader);
  write_file(root / "lib" / "offset.glsl", "float offset() { return 0.5; }\n");
  const gpu::ShaderRequest request{"main.comp", {}, {{"VALUE", "2"}}};

  gpu::ShaderCompiler first({root}, cache);
  auto compiled = first.compile(request);
  EXPECT_EQ(first.stats().compiled, 1u);
  EXPECT_EQ(first.stats().cache_hits, 0u);

  // A new compiler (a new process, in effect) finds the entry on disk.
  gpu::ShaderCompiler second({root}, cache);
  EXPECT_EQ(second.compile(request), compiled);
  EXPECT_EQ(second.stats().compiled, 0u);
  EXPECT_EQ(second.stats().cache_hits, 1u);

  std::vector<fs::path> entries;
  for (const auto& entry : fs::directory_iterator(cache)) entries.push_back(entry.path());
  ASSERT_EQ(entries.size(), 1u);
  EXPECT_EQ(entries[0].extension(), ".spv");

  // Damaged entries: flipped bytes, then a truncated file, then garbage.
  {
    std::fstream file(entries[0], std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(40);
    file.write("\xff\xfe\xfd\xfc", 4);
  }
  EXPECT_EQ(second.compile(request), compiled);
  EXPECT_EQ(second.stats().compiled, 1u);
  fs::resize_file(entries[0], fs::file_size(entries[0]) - 8);
  EXPECT_EQ(second.compile(request), compiled);
  EXPECT_EQ(second.stats().compiled, 2u);
  write_file(entries[0], "not spir-v at all");
  EXPECT_EQ(second.compile(request), compiled);
  EXPECT_EQ(second.stats().compiled, 3u);
  // The rewritten entry is good again.
  EXPECT_EQ(second.compile(request), compiled);
  EXPECT_EQ(second.stats().cache_hits, 2u);
  EXPECT_FLOAT_EQ(run_value_shader(context(), second.compile(request)), 2.5f);

  // Editing an included file changes the key.
  write_file(root / "lib" / "offset.glsl", "float offset() { return 0.75; }\n");
  auto edited = second.compile(request);
  EXPECT_EQ(second.stats().compiled, 4u);
  EXPECT_FLOAT_EQ(run_value_shader(context(), edited), 2.75f);
}

TEST(ShaderCompilerPaths, DefaultsComeFromTheEnvironment) {
  EXPECT_FALSE(gpu::ShaderCompiler::default_shader_root().empty());
  EXPECT_FALSE(gpu::ShaderCompiler::default_cache_dir().empty());
  EXPECT_EQ(gpu::ShaderCompiler::stage_from_extension("a/b.frag"), VK_SHADER_STAGE_FRAGMENT_BIT);
  EXPECT_EQ(gpu::ShaderCompiler::stage_from_extension("x.glsl"), VkShaderStageFlagBits(0));
}

TEST_F(ShaderCompilerTest, CompilesTheRepositoryFrameInclude) {
  fs::path root = fs::path(VOXGI_SOURCE_DIR) / "shaders";
  if (!fs::exists(root / "lib" / "frame.glsl")) GTEST_SKIP() << "shaders/lib/frame.glsl absent";
  auto dir = make_temp_dir("voxgi-shaders");
  write_file(dir / "uses_frame.comp",
             "#version 460\n#include \"lib/frame.glsl\"\nlayout(local_size_x = 1) in;\n"
             "void main() {}\n");
  gpu::ShaderCompiler compiler({dir, root}, "");
  EXPECT_NO_THROW(compiler.compile({"uses_frame.comp"}));
}

}  // namespace
}  // namespace voxgi::test
