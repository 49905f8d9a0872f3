#pragma once
// GLSL -> SPIR-V at run time with glslang: #include (relative to the including file, then
// the shader roots), defines, a disk cache keyed by the hash of every source involved, and
// errors that name the file and line.

#include <vulkan/vulkan.h>

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

#include "engine/gpu/error.hpp"

namespace voxgi::gpu {

struct ShaderDefine {
  std::string name;
  std::string value;  // "" defines the name as 1
};

struct ShaderRequest {
  std::filesystem::path path;  // relative to a shader root, or absolute
  // 0: deduced from the extension (.vert .geom .frag .comp)
  VkShaderStageFlagBits stage = static_cast<VkShaderStageFlagBits>(0);
  std::vector<ShaderDefine> defines;
};

// A compile or link failure: one "<file>:<line>: error: <message>" line per error, the file
// being the one where the error is (an included file when it is there), followed by the
// include chain when the error is in an included file.
class ShaderError : public Error {
 public:
  explicit ShaderError(const std::string& message) : Error(message) {}
};

class ShaderCompiler {
 public:
  struct Stats {
    uint64_t compiled = 0;    // glslang runs
    uint64_t cache_hits = 0;  // loaded from the disk cache
  };

  // roots: include search dirs (typically the shaders/ folder). cache_dir: "" disables the
  // disk cache; otherwise it is created when needed.
  ShaderCompiler(std::vector<std::filesystem::path> roots, std::filesystem::path cache_dir);

  // Throws ShaderError for GLSL errors, Error for a missing file or an unknown extension.
  // Thread-safe.
  std::vector<uint32_t> compile(const ShaderRequest& request);

  Stats stats() const { return {compiled_.load(), cache_hits_.load()}; }
  const std::vector<std::filesystem::path>& roots() const { return roots_; }
  const std::filesystem::path& cache_dir() const { return cache_dir_; }

  // Env VOXGI_SHADER_DIR, else the build's <repo>/shaders.
  static std::filesystem::path default_shader_root();
  // Env VOXGI_SHADER_CACHE, else $XDG_CACHE_HOME/voxgi/spirv, else ~/.cache/voxgi/spirv.
  static std::filesystem::path default_cache_dir();
  // The stage for a file extension (.vert .geom .frag .comp), or 0.
  static VkShaderStageFlagBits stage_from_extension(const std::filesystem::path& path);

 private:
  std::filesystem::path resolve_main(const std::filesystem::path& path) const;

  std::vector<std::filesystem::path> roots_;
  std::filesystem::path cache_dir_;
  std::atomic<uint64_t> compiled_{0};
  std::atomic<uint64_t> cache_hits_{0};
};

}  // namespace voxgi::gpu
