#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "engine/gpu/context.hpp"
#include "engine/gpu/error.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

using ContextTest = GpuTest;

TEST_F(ContextTest, CreatesDeviceAndPrintsSummary) {
  gpu::Context& gpu = context();
  std::string summary = gpu.device_summary();
  std::cout << "device: " << summary << std::endl;
  EXPECT_NE(summary.find(gpu.device_name()), std::string::npos);
  EXPECT_NE(summary.find("API 1.3"), std::string::npos);
  EXPECT_NE(gpu.device(), VK_NULL_HANDLE);
  EXPECT_NE(gpu.queue(), VK_NULL_HANDLE);
  EXPECT_NE(gpu.command_pool(), VK_NULL_HANDLE);
  EXPECT_GE(gpu.features().max_push_descriptors, 16u);
  EXPECT_GT(gpu.features().timestamp_period_ns, 0.0f);
}

TEST_F(ContextTest, DeviceFeaturesHaveOneGraphNameEach) {
  const std::map<std::string, double> values = gpu::device_feature_values(context().features());
  ASSERT_EQ(values.size(), gpu::device_feature_names().size());
  for (const gpu::DeviceFeatureName& f : gpu::device_feature_names()) {
    ASSERT_TRUE(values.count(f.name)) << f.name;
    EXPECT_EQ(f.name.rfind("device.", 0), 0u) << f.name;
    EXPECT_FALSE(f.doc.empty()) << f.name;
  }
  // What the context enables is what it reports.
  EXPECT_EQ(values.at("device.conservative_rasterization") != 0.0,
            context().features().conservative_rasterization);
  EXPECT_EQ(values.at("device.geometry_shader") != 0.0, context().features().geometry_shader);
}

TEST_F(ContextTest, SamplersAreCachedPerKind) {
  gpu::Context& gpu = context();
  const gpu::SamplerKind kinds[] = {
      gpu::SamplerKind::LinearClamp,          gpu::SamplerKind::LinearRepeat,
      gpu::SamplerKind::NearestClamp,         gpu::SamplerKind::ShadowCompare,
      gpu::SamplerKind::LinearClampMipmapped, gpu::SamplerKind::LinearRepeatMipmapped,
      gpu::SamplerKind::SceneTexture};
  std::vector<VkSampler> seen;
  for (auto kind : kinds) {
    VkSampler sampler = gpu.sampler(kind);
    ASSERT_NE(sampler, VK_NULL_HANDLE);
    EXPECT_EQ(sampler, gpu.sampler(kind));
    for (VkSampler other : seen) EXPECT_NE(sampler, other);
    seen.push_back(sampler);
  }
}

TEST_F(ContextTest, ImmediateSubmitRunsAndPropagatesExceptions) {
  gpu::Context& gpu = context();
  bool recorded = false;
  gpu.immediate_submit([&](VkCommandBuffer cmd) {
    EXPECT_NE(cmd, VK_NULL_HANDLE);
    recorded = true;
  });
  EXPECT_TRUE(recorded);
  EXPECT_THROW(gpu.immediate_submit([](VkCommandBuffer) { throw gpu::Error("stop"); }), gpu::Error);
  // The context still works afterwards.
  gpu.immediate_submit([](VkCommandBuffer) {});
}

TEST_F(ContextTest, ValidationMessagesAreRecordedAndObserved) {
  gpu::Context& gpu = context();
  std::vector<std::string> observed;
  gpu.set_validation_observer([&](const std::string& message) { observed.push_back(message); });
  // usage 0 breaks VUID-VkBufferCreateInfo-usage-requiredbitmask; the driver still copes.
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = 16;
  info.usage = 0;
  VkBuffer buffer = VK_NULL_HANDLE;
  std::cerr << "(the next validation message is expected)" << std::endl;
  vkCreateBuffer(gpu.device(), &info, nullptr, &buffer);
  if (buffer) vkDestroyBuffer(gpu.device(), buffer, nullptr);
  gpu.set_validation_observer(nullptr);
  EXPECT_GE(gpu.validation_message_count(), 1u);
  ASSERT_FALSE(observed.empty());
  EXPECT_NE(observed[0].find("usage"), std::string::npos) << observed[0];
  gpu.clear_validation_messages();
  EXPECT_EQ(gpu.validation_message_count(), 0u);
}

TEST_F(ContextTest, ListDevicesNamesTheDevice) {
  auto devices = gpu::Context::list_devices();
  ASSERT_FALSE(devices.empty());
  bool found = false;
  for (const auto& line : devices)
    found = found || line.find(context().device_name()) != std::string::npos;
  EXPECT_TRUE(found);
}

TEST_F(ContextTest, UnknownDeviceGivesErrorListingDevices) {
  gpu::ContextOptions options;
  options.device = "no-such-gpu-xyz";
  try {
    gpu::Context unused(options);
    FAIL() << "expected gpu::Error";
  } catch (const gpu::Error& error) {
    std::string message = error.what();
    EXPECT_NE(message.find("no-such-gpu-xyz"), std::string::npos) << message;
    EXPECT_NE(message.find("available devices"), std::string::npos) << message;
    EXPECT_NE(message.find(context().device_name()), std::string::npos) << message;
  }
  options.device = "97";
  EXPECT_THROW(gpu::Context unused(options), gpu::Error);
}

TEST_F(ContextTest, DeviceChosenByNameSubstringCaseInsensitive) {
  std::string name = context().device_name();
  std::string upper;
  for (char c : name.substr(0, 4)) upper += static_cast<char>(std::toupper(c));
  gpu::ContextOptions options;
  options.device = upper;
  gpu::Context second(options);
  EXPECT_EQ(second.device_name(), name);
}

// The pipeline cache is written when a context is released and read by the next one for the
// same device and driver; a file of another driver or garbage is ignored, not handed over.
TEST_F(ContextTest, PipelineCacheIsWrittenAndReadBack) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("voxgi_pipeline_cache_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  gpu::ContextOptions options;
  options.validation = true;
  options.pipeline_cache_dir = dir;
  std::filesystem::path file;
  {
    gpu::Context first(options);
    ASSERT_NE(first.pipeline_cache(), VK_NULL_HANDLE);
    file = dir / std::filesystem::path(first.pipeline_cache_path()).filename();
  }
  ASSERT_TRUE(std::filesystem::exists(file)) << file;
  std::ifstream in(file, std::ios::binary);
  VkPipelineCacheHeaderVersionOne header{};
  in.read(reinterpret_cast<char*>(&header), sizeof header);
  EXPECT_EQ(header.headerVersion, VK_PIPELINE_CACHE_HEADER_VERSION_ONE);
  EXPECT_EQ(header.vendorID, context().properties().vendorID);
  EXPECT_EQ(header.deviceID, context().properties().deviceID);
  { gpu::Context second(options); }  // reads it back (validation on)
  std::ofstream(file, std::ios::binary | std::ios::trunc) << std::string(100, 'x');
  { gpu::Context third(options); }  // garbage: starts empty
  std::filesystem::remove_all(dir);
}

TEST(ErrorTest, CheckNamesTheResultAndWhatFailed) {
  EXPECT_NO_THROW(gpu::check(VK_SUCCESS, "nothing"));
  EXPECT_NO_THROW(gpu::check(VK_INCOMPLETE, "partial"));
  try {
    gpu::check(VK_ERROR_OUT_OF_DEVICE_MEMORY, "allocating the voxel volume");
    FAIL() << "expected gpu::Error";
  } catch (const gpu::Error& error) {
    std::string message = error.what();
    EXPECT_NE(message.find("allocating the voxel volume"), std::string::npos);
    EXPECT_NE(message.find("VK_ERROR_OUT_OF_DEVICE_MEMORY"), std::string::npos);
  }
  EXPECT_STREQ(gpu::to_string(VK_ERROR_DEVICE_LOST), "VK_ERROR_DEVICE_LOST");
}

}  // namespace
}  // namespace voxgi::test
