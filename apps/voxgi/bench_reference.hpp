#pragma once
// Reference images for `voxgi bench`: rendered once per scene, camera and resolution by the
// reference graph and cached on disk under a hash of everything they depend on, so a second
// bench run (or another shard) reuses them.

#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include "apps/voxgi/bench_spec.hpp"
#include "engine/graph/graph_desc.hpp"
#include "engine/image/image.hpp"
#include "engine/scene/scene.hpp"

namespace voxgi::cli {

struct ReferenceImages {
  std::string key;
  bool cache_hit = false;
  image::ImageRGBA32F linear;
  std::optional<image::ImageRGBA32F> indirect;
  // The variance of `indirect`'s per-pixel mean (a path tracer's; none for image references).
  std::optional<image::ImageRGBA32F> indirect_variance;
  std::filesystem::path display_png;  // in the cache
};

// Hash of: the scene (file bytes, plus the other files of a .gltf's folder; the scene data of
// a built-in), the camera, the resolution, the reference graph file, the shader sources of its
// pass families and shaders/lib, its overrides and its frame count.
std::string reference_key(const BenchReference& reference, const graph::GraphDesc& desc,
                          const std::string& scene_source, const scene::Scene& scene,
                          const scene::Camera& camera, uint32_t width, uint32_t height,
                          const std::filesystem::path& shader_root);

// Env VOXGI_REFERENCE_CACHE, else $XDG_CACHE_HOME/voxgi/references, else
// ~/.cache/voxgi/references.
std::filesystem::path default_reference_cache_dir();

// The bench file's image reference ("reference": {"image", "indirect"}) with a key hashed from
// the files' bytes. Throws GraphError at `reference.image` or `reference.indirect`, naming the
// file, when one cannot be read or the two differ in size.
ReferenceImages read_reference_images(const BenchReference& reference);

// A display-referred picture of linear radiance for the report, where no graph's display
// transform ran (image references): the ACES curve HDR-FLIP uses, then the sRGB encoding.
image::ImageRGBA32F display_picture(const image::ImageRGBA32F& linear);

class ReferenceCache {
 public:
  explicit ReferenceCache(std::filesystem::path dir) : dir_(std::move(dir)) {}
  const std::filesystem::path& dir() const { return dir_; }

  // The cached entry, or nullopt when there is none (an unreadable entry counts as none).
  std::optional<ReferenceImages> find(const std::string& key) const;
  // True when an entry for `key` is present (without reading it).
  bool has_entry(const std::string& key) const;
  // Stores a rendered reference: `outputs` must hold "linear" and "display", may hold
  // "indirect" and "indirect_variance". Written to a temporary folder and renamed, so readers never
  // see half an entry.
  ReferenceImages store(const std::string& key,
                        const std::map<std::string, image::ImageRGBA32F>& outputs,
                        const std::string& description_json);

 private:
  std::filesystem::path dir_;
};

}  // namespace voxgi::cli
