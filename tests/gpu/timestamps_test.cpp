#include <gtest/gtest.h>

#include "engine/gpu/timestamps.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

using TimestampTest = GpuTest;

TEST_F(TimestampTest, ValuesAreMonotone) {
  if (!context().features().timestamps) GTEST_SKIP() << "device has no timestamps";
  gpu::TimestampQueries queries(context(), 4);
  ASSERT_TRUE(queries.supported());
  uint32_t indices[5];
  context().immediate_submit([&](VkCommandBuffer cmd) {
    queries.reset(cmd);
    indices[0] = queries.write(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT);
    indices[1] = queries.write(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    indices[2] = queries.write(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    indices[3] = queries.write(cmd, VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT);
    indices[4] = queries.write(cmd, VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT);
  });
  for (uint32_t i = 0; i < 4; ++i) EXPECT_EQ(indices[i], i);
  EXPECT_EQ(indices[4], gpu::TimestampQueries::kInvalid);
  auto values = queries.read();
  ASSERT_EQ(values.size(), 4u);
  for (size_t i = 1; i < values.size(); ++i) {
    EXPECT_GE(values[i], values[i - 1]);
    EXPECT_GE(queries.milliseconds(values[i - 1], values[i]), 0.0);
  }
  EXPECT_LT(queries.milliseconds(values[0], values[3]), 10000.0);
}

}  // namespace
}  // namespace voxgi::test
