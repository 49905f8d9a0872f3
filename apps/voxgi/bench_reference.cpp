#include "apps/voxgi/bench_reference.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <vector>

#include "apps/voxgi/bench_hash.hpp"
#include "apps/voxgi/bench_results.hpp"
#include "engine/image/flip.hpp"

namespace voxgi::cli {
namespace {

namespace fs = std::filesystem;

// Every regular file under `dir`, sorted, with its path relative to `base`.
void hash_tree(Hasher& hasher, const fs::path& dir, const fs::path& base) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return;
  std::vector<fs::path> files;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(dir, ec)) {
    if (entry.is_regular_file(ec)) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) {
    hasher.add(file.lexically_relative(base).generic_string());
    hasher.add_file(file);
  }
}

// What a built-in scene is made of: its geometry, materials, lights and textures.
void hash_scene_data(Hasher& hasher, const scene::Scene& scene) {
  for (const scene::Mesh& mesh : scene.meshes) {
    for (const scene::Primitive& primitive : mesh.primitives) {
      hasher.add_bytes(primitive.vertices.data(),
                       primitive.vertices.size() * sizeof(scene::Vertex));
      hasher.add_bytes(primitive.indices.data(), primitive.indices.size() * sizeof(uint32_t));
      hasher.add_value(primitive.material);
    }
  }
  for (const scene::Material& m : scene.materials) {
    hasher.add_value(m.base_color).add_value(m.metallic).add_value(m.roughness);
    hasher.add_value(m.emissive).add_value(m.double_sided).add_value(m.alpha_mode);
  }
  for (const scene::Light& l : scene.lights) {
    hasher.add_value(l.type).add_value(l.color).add_value(l.intensity).add_value(l.range);
    hasher.add_value(l.inner_cone).add_value(l.outer_cone).add_value(l.position);
    hasher.add_value(l.direction);
  }
  for (const scene::Texture& t : scene.textures) {
    hasher.add_bytes(t.pixels.data(), t.pixels.size());
  }
  for (const scene::Node& n : scene.nodes) {
    hasher.add_value(n.world).add_value(n.mesh);
  }
}

}  // namespace

std::string reference_key(const BenchReference& reference, const graph::GraphDesc& desc,
                          const std::string& scene_source, const scene::Scene& scene,
                          const scene::Camera& camera, uint32_t width, uint32_t height,
                          const fs::path& shader_root) {
  Hasher hasher;
  hasher.add("voxgi-reference-1");
  const fs::path scene_path(scene_source);
  const std::string ext = scene_path.extension().string();
  if (ext == ".gltf" || ext == ".glb") {
    hasher.add("file");
    hasher.add_file(scene_path);
    // A .gltf names its buffers and images by relative URI; the folder's other files cover
    // them without parsing the file again.
    if (ext == ".gltf") hash_tree(hasher, scene_path.parent_path(), scene_path.parent_path());
  } else {
    hasher.add("builtin:" + scene_source);
    hash_scene_data(hasher, scene);
  }
  hasher.add(camera.name).add_value(camera.yfov).add_value(camera.znear).add_value(camera.zfar);
  hasher.add_value(camera.aspect).add_value(camera.world);
  hasher.add_value(width).add_value(height);
  hasher.add_file(reference.file);
  for (const std::string& family : desc.families()) {
    hasher.add(family);
    hash_tree(hasher, shader_root / family, shader_root);
  }
  hash_tree(hasher, shader_root / "lib", shader_root);
  for (const auto& [key, value] : reference.set) hasher.add(key).add(value);
  hasher.add_value(reference.frames);
  return hasher.hex();
}

ReferenceImages read_reference_images(const BenchReference& reference) {
  Hasher hasher;
  hasher.add("voxgi-reference-image-1");
  const auto read = [&](const BenchReferenceImage& source, const std::string& field) {
    try {
      hasher.add_file(source.file);
      return image::read_exr(source.file);
    } catch (const std::exception& e) {
      throw graph::GraphError(graph::Diagnostic{
          source.loc, "", field,
          "cannot read '" + source.file_as_written + "': " + std::string(e.what()), ""});
    }
  };
  const auto size_text = [](const image::ImageRGBA32F& picture) {
    return std::to_string(picture.width) + "x" + std::to_string(picture.height);
  };
  ReferenceImages images;
  images.linear = read(reference.image, "reference.image");
  if (!reference.indirect.file_as_written.empty()) {
    images.indirect = read(reference.indirect, "reference.indirect");
    if (images.indirect->width != images.linear.width ||
        images.indirect->height != images.linear.height) {
      throw graph::GraphError(graph::Diagnostic{
          reference.indirect.loc, "", "reference.indirect",
          "'" + reference.indirect.file_as_written + "' is " + size_text(*images.indirect) +
              " but the image '" + reference.image.file_as_written + "' is " +
              size_text(images.linear),
          ""});
    }
  }
  images.key = hasher.hex();
  return images;
}

image::ImageRGBA32F display_picture(const image::ImageRGBA32F& linear) {
  image::ImageRGBA32F picture = linear;
  for (size_t i = 0; i + 3 < picture.pixels.size(); i += 4) {
    for (size_t c = 0; c < 3; ++c) {
      const float v = picture.pixels[i + c];
      const double mapped =
          std::clamp(image::flip_tone_map(std::isfinite(v) ? std::max(0.0f, v) : 0.0f), 0.0, 1.0);
      picture.pixels[i + c] = static_cast<float>(
          mapped <= 0.0031308 ? 12.92 * mapped : 1.055 * std::pow(mapped, 1.0 / 2.4) - 0.055);
    }
    picture.pixels[i + 3] = 1.0f;
  }
  return picture;
}

fs::path default_reference_cache_dir() {
  if (const char* env = std::getenv("VOXGI_REFERENCE_CACHE"); env && *env) return env;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
    return fs::path(xdg) / "voxgi" / "references";
  }
  if (const char* home = std::getenv("HOME"); home && *home) {
    return fs::path(home) / ".cache" / "voxgi" / "references";
  }
  return fs::temp_directory_path() / "voxgi-references";
}

bool ReferenceCache::has_entry(const std::string& key) const {
  std::error_code ec;
  return fs::is_regular_file(dir_ / key / "linear.exr", ec) &&
         fs::is_regular_file(dir_ / key / "display.png", ec);
}

std::optional<ReferenceImages> ReferenceCache::find(const std::string& key) const {
  const fs::path entry = dir_ / key;
  std::error_code ec;
  if (!has_entry(key)) return std::nullopt;
  ReferenceImages images;
  images.key = key;
  images.cache_hit = true;
  try {
    images.linear = image::read_exr(entry / "linear.exr");
    if (fs::is_regular_file(entry / "indirect.exr", ec)) {
      images.indirect = image::read_exr(entry / "indirect.exr");
    }
    if (fs::is_regular_file(entry / "indirect_variance.exr", ec)) {
      images.indirect_variance = image::read_exr(entry / "indirect_variance.exr");
    }
  } catch (const image::ImageError&) {
    return std::nullopt;  // damaged: render it again
  }
  images.display_png = entry / "display.png";
  return images;
}

ReferenceImages ReferenceCache::store(const std::string& key,
                                      const std::map<std::string, image::ImageRGBA32F>& outputs,
                                      const std::string& description_json) {
  const fs::path entry = dir_ / key;
  const fs::path temp = dir_ / (key + ".tmp-" + std::to_string(::getpid()));
  std::error_code ec;
  fs::create_directories(temp, ec);
  if (ec) {
    throw std::runtime_error("reference cache '" + dir_.string() +
                             "': cannot create a folder: " + ec.message());
  }
  image::write_exr(temp / "linear.exr", outputs.at("linear"), image::ExrPixelType::Float);
  if (outputs.count("indirect")) {
    image::write_exr(temp / "indirect.exr", outputs.at("indirect"), image::ExrPixelType::Float);
  }
  if (outputs.count("indirect_variance")) {
    image::write_exr(temp / "indirect_variance.exr", outputs.at("indirect_variance"),
                     image::ExrPixelType::Float);
  }
  image::write_png(temp / "display.png", outputs.at("display"));
  write_file_atomically(temp / "reference.json", description_json);
  fs::rename(temp, entry, ec);
  if (ec) {
    // Another process (a parallel shard) stored the same key first: keep its entry.
    fs::remove_all(temp, ec);
  }
  ReferenceImages images;
  images.key = key;
  images.linear = outputs.at("linear");
  if (outputs.count("indirect")) images.indirect = outputs.at("indirect");
  if (outputs.count("indirect_variance"))
    images.indirect_variance = outputs.at("indirect_variance");
  images.display_png = entry / "display.png";
  return images;
}

}  // namespace voxgi::cli
