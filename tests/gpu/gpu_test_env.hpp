#pragma once
// Shared set-up for GPU tests: one validated Vulkan context per test process, and a
// fixture that fails any test during which the validation layer said something.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "engine/gpu/context.hpp"

namespace voxgi::test {

// Created on first use with validation and synchronization validation on; the device comes
// from env VOXGI_TEST_DEVICE when set. Lives until the process exits.
gpu::Context& gpu_context();

// A fresh, empty directory under the system temp dir, unique per call; removed when the
// process exits.
std::filesystem::path make_temp_dir(const std::string& prefix);

class GpuTest : public ::testing::Test {
 protected:
  void SetUp() override;
  // Fails the test (ADD_FAILURE, listing the messages) if any validation message was
  // recorded during it, then clears them.
  void TearDown() override;
  gpu::Context& context() { return gpu_context(); }
};

}  // namespace voxgi::test
