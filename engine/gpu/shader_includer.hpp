#pragma once
// Internal to engine/gpu: resolving and reading GLSL includes, for glslang and for the
// cache key.

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glslang/Public/ShaderLang.h>

namespace voxgi::gpu {

// Reads a whole file; nullopt when it cannot be read.
std::optional<std::string> read_text_file(const std::filesystem::path& path);

// Where `#include "name"` (local) or `#include <name>` (system) written in `includer`
// points: the includer's folder first (local only), then each root. nullopt if nowhere.
std::optional<std::filesystem::path> resolve_include(
    const std::string& name, const std::filesystem::path& includer, bool local,
    const std::vector<std::filesystem::path>& roots);

// Every file `main` includes, recursively and depth first, each once, with its contents:
// what the cache key hashes. Includes that cannot be resolved are skipped (glslang reports
// them).
std::vector<std::pair<std::filesystem::path, std::string>> collect_includes(
    const std::filesystem::path& main, const std::string& main_source,
    const std::vector<std::filesystem::path>& roots);

// glslang's file-system includer; remembers who included whom for error messages.
class ShaderIncluder : public glslang::TShader::Includer {
 public:
  explicit ShaderIncluder(std::vector<std::filesystem::path> roots) : roots_(std::move(roots)) {}
  IncludeResult* includeLocal(const char* header, const char* includer, size_t depth) override;
  IncludeResult* includeSystem(const char* header, const char* includer, size_t depth) override;
  void releaseInclude(IncludeResult* result) override;

  // "included from A, included from B" for a file reached through includes, else "".
  std::string include_chain(const std::string& file) const;

 private:
  IncludeResult* include(const char* header, const char* includer, size_t depth, bool local);
  std::vector<std::filesystem::path> roots_;
  std::map<std::string, std::string> included_by_;
};

}  // namespace voxgi::gpu
