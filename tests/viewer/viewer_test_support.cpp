#include "tests/viewer/viewer_test_support.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

namespace voxgi::test {

std::string test_graph_text(double ambient) {
  return R"json({
  "name": "viewer-test",
  "variants": {
    "bright": { "doc": "more ambient light", "set": { "ambient.radiance": 0.6 } },
    "small_shadows": { "doc": "smaller shadow maps", "set": { "shadows.resolution": 64 } }
  },
  "resources": {
    "gbuffer.base_color": { "type": "image2d", "format": "rgba8_srgb", "size": "viewport" },
    "gbuffer.normal":     { "type": "image2d", "format": "rgba16f",    "size": "viewport" },
    "gbuffer.material":   { "type": "image2d", "format": "rgba8",      "size": "viewport" },
    "gbuffer.emission":   { "type": "image2d", "format": "rgba16f",    "size": "viewport" },
    "gbuffer.depth":      { "type": "image2d", "format": "d32f",       "size": "viewport" },
    "shadow.maps":        { "type": "image2d", "persistent": true },
    "shadow.matrices":    { "type": "buffer", "persistent": true },
    "light.direct":       { "type": "image2d", "format": "rgba16f", "size": "viewport" },
    "gi.diffuse":         { "type": "image2d", "format": "rgba16f", "size": "viewport" },
    "hdr":                { "type": "image2d", "format": "rgba16f", "size": "viewport" },
    "ldr":                { "type": "image2d", "format": "rgba8",   "size": "viewport" }
  },
  "passes": [
    { "name": "gbuffer", "type": "common.gbuffer",
      "out": { "base_color": "gbuffer.base_color", "normal": "gbuffer.normal",
               "material": "gbuffer.material", "emission": "gbuffer.emission",
               "depth": "gbuffer.depth" } },
    { "name": "shadows", "type": "common.shadow_maps", "when": "scene.has_lights",
      "params": { "resolution": 256, "max_lights": 4 },
      "out": { "maps": "shadow.maps", "matrices": "shadow.matrices" } },
    { "name": "lighting", "type": "common.deferred_lighting",
      "in": { "base_color": "gbuffer.base_color", "normal": "gbuffer.normal",
              "material": "gbuffer.material", "emission": "gbuffer.emission",
              "depth": "gbuffer.depth", "shadow_maps": "shadow.maps",
              "shadow_matrices": "shadow.matrices" },
      "out": { "radiance": "light.direct" } },
    { "name": "ambient", "type": "common.ambient", "params": { "radiance": )json" +
         std::to_string(ambient) + R"json( },
      "in": { "base_color": "gbuffer.base_color", "material": "gbuffer.material",
              "depth": "gbuffer.depth" },
      "out": { "radiance": "gi.diffuse" } },
    { "name": "composite", "type": "common.composite",
      "in": { "direct": "light.direct", "indirect_diffuse": "gi.diffuse" },
      "out": { "radiance": "hdr" } },
    { "name": "display", "type": "common.display_transform",
      "in": { "radiance": "hdr" }, "out": { "display": "ldr" } }
  ],
  "outputs": { "display": "ldr", "linear": "hdr" }
}
)json";
}

namespace {

std::string base64(const std::vector<uint8_t>& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t n = (uint32_t(bytes[i]) << 16) |
                       (i + 1 < bytes.size() ? uint32_t(bytes[i + 1]) << 8 : 0u) |
                       (i + 2 < bytes.size() ? uint32_t(bytes[i + 2]) : 0u);
    out += table[(n >> 18) & 63];
    out += table[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? table[n & 63] : '=';
  }
  return out;
}

template <typename T>
void append(std::vector<uint8_t>& bytes, std::initializer_list<T> values) {
  for (T v : values) {
    const auto* p = reinterpret_cast<const uint8_t*>(&v);
    bytes.insert(bytes.end(), p, p + sizeof(T));
  }
}

}  // namespace

std::string animated_gltf_text() {
  // Buffer layout: quad positions (4 × vec3, 48 B), normals (48 B), indices (6 × u16, 12 B),
  // animation times (2 floats, 8 B), translations (2 × vec3, 24 B).
  std::vector<uint8_t> bytes;
  append<float>(bytes, {-0.5f, 0, -0.5f, 0.5f, 0, -0.5f, 0.5f, 0, 0.5f, -0.5f, 0, 0.5f});
  append<float>(bytes, {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0});
  append<uint16_t>(bytes, {0, 2, 1, 0, 3, 2});
  append<float>(bytes, {0.0f, 1.0f});
  append<float>(bytes, {-1.0f, 0.01f, 0.0f, 1.0f, 0.01f, 0.0f});
  const std::string uri = "data:application/octet-stream;base64," + base64(bytes);
  return R"json({
  "asset": { "version": "2.0" },
  "extensionsUsed": [ "KHR_lights_punctual" ],
  "extensions": { "KHR_lights_punctual": { "lights": [
    { "type": "point", "intensity": 6.0, "color": [1, 1, 1] } ] } },
  "scene": 0,
  "scenes": [ { "nodes": [ 0, 1, 2, 3 ] } ],
  "nodes": [
    { "name": "floor", "mesh": 0, "scale": [ 4, 1, 4 ] },
    { "name": "slider", "mesh": 1, "translation": [ -1, 0.01, 0 ] },
    { "name": "lamp", "translation": [ 0, 1.5, 0.5 ],
      "extensions": { "KHR_lights_punctual": { "light": 0 } } },
    { "name": "eye", "camera": 0, "translation": [ 0, 2.5, 2.5 ],
      "rotation": [ -0.3826834, 0, 0, 0.9238795 ] }
  ],
  "cameras": [ { "name": "overview", "type": "perspective",
                 "perspective": { "yfov": 0.9, "znear": 0.05, "zfar": 50 } } ],
  "materials": [
    { "name": "grey", "pbrMetallicRoughness": { "baseColorFactor": [ 0.3, 0.3, 0.3, 1 ],
                                                  "metallicFactor": 0, "roughnessFactor": 1 } },
    { "name": "white", "pbrMetallicRoughness": { "baseColorFactor": [ 0.9, 0.9, 0.9, 1 ],
                                                   "metallicFactor": 0, "roughnessFactor": 1 } }
  ],
  "meshes": [
    { "primitives": [ { "attributes": { "POSITION": 0, "NORMAL": 1 }, "indices": 2, "material": 0 } ] },
    { "primitives": [ { "attributes": { "POSITION": 0, "NORMAL": 1 }, "indices": 2, "material": 1 } ] }
  ],
  "animations": [ { "name": "slide",
    "samplers": [ { "input": 3, "output": 4, "interpolation": "LINEAR" } ],
    "channels": [ { "sampler": 0, "target": { "node": 1, "path": "translation" } } ] } ],
  "accessors": [
    { "bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
      "min": [ -0.5, 0, -0.5 ], "max": [ 0.5, 0, 0.5 ] },
    { "bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3" },
    { "bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR" },
    { "bufferView": 3, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [ 0 ], "max": [ 1 ] },
    { "bufferView": 4, "componentType": 5126, "count": 2, "type": "VEC3" }
  ],
  "bufferViews": [
    { "buffer": 0, "byteOffset": 0, "byteLength": 48 },
    { "buffer": 0, "byteOffset": 48, "byteLength": 48 },
    { "buffer": 0, "byteOffset": 96, "byteLength": 12 },
    { "buffer": 0, "byteOffset": 108, "byteLength": 8 },
    { "buffer": 0, "byteOffset": 116, "byteLength": 24 }
  ],
  "buffers": [ { "byteLength": 140, "uri": ")json" +
         uri + R"json(" } ]
}
)json";
}

void write_file(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

void replace_file(const std::filesystem::path& file, const std::string& text) {
  const std::filesystem::path temp = file.string() + ".partial";
  write_file(temp, text);
  std::filesystem::rename(temp, file);
}

ImageDifference compare_images(const image::ImageRGBA32F& a, const image::ImageRGBA32F& b) {
  if (a.width != b.width || a.height != b.height) {
    throw std::invalid_argument("images of different sizes");
  }
  ImageDifference d;
  double sum = 0.0;
  for (size_t i = 0; i < a.pixels.size(); i += 4) {
    for (size_t c = 0; c < 3; ++c) {
      const double diff = std::abs(static_cast<double>(a.pixels[i + c]) - b.pixels[i + c]);
      d.max_abs = std::max(d.max_abs, diff);
      sum += diff;
    }
  }
  d.mean_abs = a.pixels.empty() ? 0.0 : sum / (static_cast<double>(a.pixels.size()) * 0.75);
  return d;
}

double mean_rgb(const image::ImageRGBA32F& picture) {
  double sum = 0.0;
  for (size_t i = 0; i < picture.pixels.size(); i += 4) {
    sum += picture.pixels[i] + picture.pixels[i + 1] + picture.pixels[i + 2];
  }
  return picture.pixels.empty() ? 0.0 : sum / (static_cast<double>(picture.pixels.size()) * 0.75);
}

size_t distinct_colors(const image::ImageRGBA32F& picture) {
  std::set<std::tuple<float, float, float>> colors;
  for (size_t i = 0; i < picture.pixels.size(); i += 4) {
    colors.emplace(picture.pixels[i], picture.pixels[i + 1], picture.pixels[i + 2]);
  }
  return colors.size();
}

bool wait_for_file(const std::filesystem::path& file, double seconds) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::milliseconds(static_cast<int>(seconds * 1000));
  while (std::chrono::steady_clock::now() < deadline) {
    if (std::filesystem::exists(file)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return std::filesystem::exists(file);
}

}  // namespace voxgi::test
