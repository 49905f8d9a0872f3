#include <gtest/gtest.h>

#include <numeric>
#include <vector>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/error.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

using BufferTest = GpuTest;

std::vector<uint32_t> ramp(size_t count, uint32_t start) {
  std::vector<uint32_t> values(count);
  std::iota(values.begin(), values.end(), start);
  return values;
}

TEST_F(BufferTest, GpuOnlyRoundTrip) {
  gpu::Buffer buffer(context(), 1024 * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                     gpu::MemoryUsage::GpuOnly, "test.gpu_only");
  EXPECT_EQ(buffer.mapped(), nullptr);
  auto values = ramp(1024, 7);
  buffer.upload_vector(values);
  EXPECT_EQ(buffer.download_vector<uint32_t>(), values);
  // A partial update at an offset leaves the rest alone.
  std::vector<uint32_t> patch{1, 2, 3};
  buffer.upload_vector(patch, 10 * sizeof(uint32_t));
  auto part = buffer.download_vector<uint32_t>(5, 8 * sizeof(uint32_t));
  EXPECT_EQ(part, (std::vector<uint32_t>{15, 16, 1, 2, 3}));
}

TEST_F(BufferTest, HostVisibleRoundTrip) {
  for (auto usage : {gpu::MemoryUsage::CpuToGpu, gpu::MemoryUsage::GpuToCpu}) {
    gpu::Buffer buffer(context(), 256, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, usage, "test.mapped");
    ASSERT_NE(buffer.mapped(), nullptr);
    auto values = ramp(64, 100);
    buffer.upload_vector(values);
    EXPECT_EQ(static_cast<const uint32_t*>(buffer.mapped())[3], 103u);
    EXPECT_EQ(buffer.download_vector<uint32_t>(), values);
  }
}

TEST_F(BufferTest, MoveKeepsTheBuffer) {
  gpu::Buffer a(context(), 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::GpuOnly,
                "test.move");
  VkBuffer handle = a.handle();
  gpu::Buffer b(std::move(a));
  EXPECT_EQ(b.handle(), handle);
  EXPECT_EQ(a.handle(), VK_NULL_HANDLE);
  b.upload_vector(ramp(16, 0));
  EXPECT_EQ(b.download_vector<uint32_t>()[15], 15u);
}

TEST_F(BufferTest, BadArgumentsThrowNamingTheBuffer) {
  gpu::Buffer buffer(context(), 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::GpuOnly,
                     "test.small");
  std::vector<uint32_t> too_many(32);
  try {
    buffer.upload_vector(too_many);
    FAIL() << "expected gpu::Error";
  } catch (const gpu::Error& error) {
    EXPECT_NE(std::string(error.what()).find("test.small"), std::string::npos) << error.what();
  }
  EXPECT_THROW(buffer.download_vector<uint32_t>(4, 60), gpu::Error);
  EXPECT_THROW(gpu::Buffer(context(), 0, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                           gpu::MemoryUsage::GpuOnly, "test.empty"),
               gpu::Error);
}

}  // namespace
}  // namespace voxgi::test
