#include "engine/gpu/pipeline_cache.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>
#include <vector>

#include "engine/gpu/error.hpp"

namespace voxgi::gpu {

namespace fs = std::filesystem;

namespace {

// The data loaded only when its header (VkPipelineCacheHeaderVersionOne) names this device and
// driver; some drivers misbehave on data from another.
bool header_matches(const std::vector<char>& data, const VkPhysicalDeviceProperties& properties) {
  VkPipelineCacheHeaderVersionOne header{};
  if (data.size() < sizeof header) return false;
  std::memcpy(&header, data.data(), sizeof header);
  return header.headerSize >= sizeof header &&
         header.headerVersion == VK_PIPELINE_CACHE_HEADER_VERSION_ONE &&
         header.vendorID == properties.vendorID && header.deviceID == properties.deviceID &&
         std::memcmp(header.pipelineCacheUUID, properties.pipelineCacheUUID, VK_UUID_SIZE) == 0;
}

std::string uuid_text(const uint8_t (&uuid)[VK_UUID_SIZE]) {
  static const char digits[] = "0123456789abcdef";
  std::string text;
  for (uint8_t byte : uuid) {
    text += digits[byte >> 4];
    text += digits[byte & 15];
  }
  return text;
}

}  // namespace

PipelineCacheFile::PipelineCacheFile(VkDevice device, const VkPhysicalDeviceProperties& properties,
                                     fs::path dir)
    : device_(device) {
  std::vector<char> data;
  if (!dir.empty()) {
    path_ = dir / (uuid_text(properties.pipelineCacheUUID) + ".bin");
    std::error_code ec;
    if (fs::is_regular_file(path_, ec) && fs::file_size(path_, ec) < (uint64_t{1} << 30)) {
      std::ifstream in(path_, std::ios::binary);
      data.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      if (!header_matches(data, properties)) data.clear();
    }
  }
  VkPipelineCacheCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
  info.initialDataSize = data.size();
  info.pInitialData = data.empty() ? nullptr : data.data();
  check(vkCreatePipelineCache(device_, &info, nullptr, &cache_), "vkCreatePipelineCache");
}

PipelineCacheFile::~PipelineCacheFile() {
  if (!cache_) return;
  if (!path_.empty()) {
    size_t size = 0;
    std::vector<char> data;
    if (vkGetPipelineCacheData(device_, cache_, &size, nullptr) == VK_SUCCESS && size > 0) {
      data.resize(size);
      if (vkGetPipelineCacheData(device_, cache_, &size, data.data()) != VK_SUCCESS) data.clear();
      data.resize(std::min(size, data.size()));
    }
    if (!data.empty()) {
      std::error_code ec;
      fs::create_directories(path_.parent_path(), ec);
      const fs::path temporary = path_.string() + ".tmp" + std::to_string(::getpid());
      {
        std::ofstream out(temporary, std::ios::binary);
        out.write(data.data(), static_cast<std::streamsize>(data.size()));
      }
      fs::rename(temporary, path_, ec);
      if (ec) fs::remove(temporary, ec);
    }
  }
  vkDestroyPipelineCache(device_, cache_, nullptr);
}

fs::path PipelineCacheFile::default_dir() {
  if (const char* env = std::getenv("VOXGI_PIPELINE_CACHE"); env && *env) return env;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
    return fs::path(xdg) / "voxgi" / "pipelines";
  }
  if (const char* home = std::getenv("HOME"); home && *home) {
    return fs::path(home) / ".cache" / "voxgi" / "pipelines";
  }
  return {};
}

}  // namespace voxgi::gpu
