#include "tests/gpu/gpu_test_env.hpp"

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <mutex>
#include <vector>

namespace voxgi::test {

gpu::Context& gpu_context() {
  // Never destroyed: GoogleTest may still run tests from static destructors' point of view,
  // and the driver cleans up at exit.
  static gpu::Context* context = [] {
    gpu::ContextOptions options;
    options.validation = true;
    options.synchronization_validation = true;
    if (const char* device = std::getenv("VOXGI_TEST_DEVICE")) options.device = device;
    auto* created = new gpu::Context(options);
    std::cout << "[ gpu      ] " << created->device_summary() << std::endl;
    return created;
  }();
  return *context;
}

namespace {

// Removes the temp dirs of this process when it exits.
struct TempDirs {
  std::mutex mutex;
  std::vector<std::filesystem::path> dirs;
  ~TempDirs() {
    std::error_code error;
    for (const auto& dir : dirs) std::filesystem::remove_all(dir, error);
  }
};

TempDirs& temp_dirs() {
  static TempDirs dirs;
  return dirs;
}

}  // namespace

std::filesystem::path make_temp_dir(const std::string& prefix) {
  static std::atomic<uint64_t> counter{0};
  auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      (prefix + "-" + std::to_string(stamp) + "-" + std::to_string(counter++));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::lock_guard lock(temp_dirs().mutex);
  temp_dirs().dirs.push_back(dir);
  return dir;
}

void GpuTest::SetUp() {
  // Messages from before this test (e.g. another fixture's teardown) are not its fault.
  gpu_context().clear_validation_messages();
}

void GpuTest::TearDown() {
  gpu::Context& context = gpu_context();
  auto messages = context.validation_messages();
  context.clear_validation_messages();
  if (!messages.empty()) {
    std::string text;
    for (const auto& message : messages) text += "\n  " + message;
    ADD_FAILURE() << messages.size() << " Vulkan validation message(s) during this test:" << text;
  }
}

}  // namespace voxgi::test
