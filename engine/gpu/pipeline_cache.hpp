#pragma once
// A VkPipelineCache kept on disk between runs, one file per driver build
// (pipelineCacheUUID), so that pipelines compiled once are not compiled again by the driver.

#include <vulkan/vulkan.h>

#include <filesystem>

namespace voxgi::gpu {

class PipelineCacheFile {
 public:
  // Starts from `dir`/<pipelineCacheUUID>.bin when its header matches this device and driver
  // (vendor, device, UUID), else empty. An empty `dir` keeps the cache in memory only.
  PipelineCacheFile(VkDevice device, const VkPhysicalDeviceProperties& properties,
                    std::filesystem::path dir);
  // Writes the cache back (to a temporary file, then renamed) and destroys it. A cache that
  // cannot be written is dropped silently: it only saves time.
  ~PipelineCacheFile();
  PipelineCacheFile(const PipelineCacheFile&) = delete;
  PipelineCacheFile& operator=(const PipelineCacheFile&) = delete;

  VkPipelineCache handle() const { return cache_; }
  const std::filesystem::path& path() const { return path_; }

  // $VOXGI_PIPELINE_CACHE, else $XDG_CACHE_HOME/voxgi/pipelines, else
  // ~/.cache/voxgi/pipelines.
  static std::filesystem::path default_dir();

 private:
  VkDevice device_;
  VkPipelineCache cache_ = VK_NULL_HANDLE;
  std::filesystem::path path_;
};

}  // namespace voxgi::gpu
