#pragma once
// Builds small glTF files for loader tests: a JSON document plus one binary buffer, written as
// .gltf + .bin or as .glb.

#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace voxgi::test {

class GltfWriter {
 public:
  GltfWriter() {
    doc["asset"] = {{"version", "2.0"}};
    doc["scene"] = 0;
    doc["scenes"] = nlohmann::json::array({{{"nodes", nlohmann::json::array()}}});
  }

  // Appends raw bytes (4-byte aligned) as a buffer view and an accessor over them.
  template <typename T>
  int add_accessor(const std::vector<T>& values, int component_type, const std::string& type,
                   size_t count, bool normalized = false) {
    while (bin.size() % 4) bin.push_back(0);
    const size_t offset = bin.size();
    bin.resize(offset + values.size() * sizeof(T));
    std::memcpy(bin.data() + offset, values.data(), values.size() * sizeof(T));
    doc["bufferViews"].push_back(
        {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", values.size() * sizeof(T)}});
    nlohmann::json accessor = {{"bufferView", doc["bufferViews"].size() - 1},
                               {"componentType", component_type},
                               {"type", type},
                               {"count", count}};
    if (normalized) accessor["normalized"] = true;
    doc["accessors"].push_back(accessor);
    return static_cast<int>(doc["accessors"].size()) - 1;
  }
  int add_floats(const std::vector<float>& values, const std::string& type, size_t components) {
    return add_accessor(values, 5126, type, values.size() / components);
  }
  // Appends raw bytes (4-byte aligned) as a buffer view; byte_stride 0 leaves it out.
  int add_view(const std::vector<uint8_t>& bytes, size_t byte_stride = 0) {
    while (bin.size() % 4) bin.push_back(0);
    nlohmann::json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes.size()}};
    if (byte_stride) view["byteStride"] = byte_stride;
    bin.insert(bin.end(), bytes.begin(), bytes.end());
    doc["bufferViews"].push_back(view);
    return static_cast<int>(doc["bufferViews"].size()) - 1;
  }
  // An image stored in the binary buffer (as GLB exporters write them).
  int add_image(const std::vector<uint8_t>& bytes, const std::string& mime_type) {
    doc["images"].push_back({{"bufferView", add_view(bytes)}, {"mimeType", mime_type}});
    return static_cast<int>(doc["images"].size()) - 1;
  }
  int add_indices(const std::vector<uint16_t>& values) {
    return add_accessor(values, 5123, "SCALAR", values.size());
  }
  // A mesh with one primitive and a root node that shows it; returns the node index.
  int add_mesh_node(nlohmann::json primitive, nlohmann::json node = nlohmann::json::object()) {
    doc["meshes"].push_back({{"primitives", nlohmann::json::array({primitive})}});
    node["mesh"] = doc["meshes"].size() - 1;
    return add_node(node);
  }
  int add_node(nlohmann::json node, bool root = true) {
    doc["nodes"].push_back(node);
    const int index = static_cast<int>(doc["nodes"].size()) - 1;
    if (root) doc["scenes"][0]["nodes"].push_back(index);
    return index;
  }
  // A unit right triangle in the XY plane facing +Z, with UVs; returns the primitive JSON.
  nlohmann::json triangle(bool with_normals = true) {
    nlohmann::json p;
    p["attributes"]["POSITION"] = add_floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
    if (with_normals)
      p["attributes"]["NORMAL"] = add_floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
    p["attributes"]["TEXCOORD_0"] = add_floats({0, 0, 1, 0, 0, 1}, "VEC2", 2);
    p["indices"] = add_indices({0, 1, 2});
    return p;
  }

  // .gltf with the buffer in `<stem>.bin` next to it.
  void write_gltf(const std::filesystem::path& path) {
    const std::filesystem::path bin_path = path.parent_path() / (path.stem().string() + ".bin");
    finish_buffer(bin_path.filename().string());
    std::ofstream(path) << doc.dump(2);
    std::ofstream(bin_path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bin.data()), std::streamsize(bin.size()));
  }

  std::vector<uint8_t> glb_bytes() {
    finish_buffer("");
    std::string json = doc.dump();
    while (json.size() % 4) json.push_back(' ');
    std::vector<uint8_t> padded = bin;
    while (padded.size() % 4) padded.push_back(0);
    std::vector<uint8_t> out;
    out.reserve(28 + json.size() + padded.size());
    auto u32 = [&](uint32_t v) {
      for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
    };
    const uint32_t total =
        12 + 8 + uint32_t(json.size()) + (padded.empty() ? 0 : 8 + uint32_t(padded.size()));
    for (char c : {'g', 'l', 'T', 'F'}) out.push_back(uint8_t(c));
    u32(2);
    u32(total);
    u32(uint32_t(json.size()));
    u32(0x4E4F534A);  // JSON
    out.insert(out.end(), json.begin(), json.end());
    if (!padded.empty()) {
      u32(uint32_t(padded.size()));
      u32(0x004E4942);  // BIN
      out.insert(out.end(), padded.begin(), padded.end());
    }
    return out;
  }
  void write_glb(const std::filesystem::path& path) {
    const std::vector<uint8_t> bytes = glb_bytes();
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  }

  nlohmann::json doc;
  std::vector<uint8_t> bin;

 private:
  void finish_buffer(const std::string& uri) {
    if (bin.empty()) return;
    nlohmann::json buffer = {{"byteLength", bin.size()}};
    if (!uri.empty()) buffer["uri"] = uri;
    doc["buffers"] = nlohmann::json::array({buffer});
  }
};

// A minimal 2 × 1 16-bit grey PNG: texels 0x1234 and 0xffff (zlib stored block).
inline std::vector<uint8_t> sixteen_bit_grey_png() {
  return {0x89, 'P',  'N',  'G',  0x0d, 0x0a, 0x1a, 0x0a, 0,    0,    0,    13,   'I',  'H',  'D',
          'R',  0,    0,    0,    2,    0,    0,    0,    1,    16,   0,    0,    0,    0,    0x81,
          0xd9, 0xfc, 0x15, 0,    0,    0,    16,   'I',  'D',  'A',  'T',  0x78, 0x01, 0x01, 0x05,
          0x00, 0xfa, 0xff, 0x00, 0x12, 0x34, 0xff, 0xff, 0x03, 0xe6, 0x02, 0x45, 0xd2, 0xfc, 0x68,
          0x73, 0,    0,    0,    0,    'I',  'E',  'N',  'D',  0xae, 0x42, 0x60, 0x82};
}

// Base64 (RFC 4648, padded), for data URIs.
inline std::string base64(const std::vector<uint8_t>& bytes) {
  static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t v = uint32_t(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= uint32_t(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) v |= bytes[i + 2];
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[v & 63] : '=';
  }
  return out;
}

// A document with a node hierarchy, a point light, a camera, an emissive material and indices:
// the fuzzers' glTF seed.
inline GltfWriter hierarchy_document() {
  GltfWriter w;
  const int child = w.add_node({{"name", "child"}, {"translation", {0, 0, -1}}}, false);
  w.doc["meshes"].push_back({{"primitives", nlohmann::json::array({w.triangle()})}});
  w.doc["nodes"][child]["mesh"] = 0;
  w.add_node({{"name", "parent"}, {"children", {child}}, {"scale", {1, 2, 1}}});
  w.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  w.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "point"}, {"color", {1, 1, 1}}, {"intensity", 20}}};
  w.add_node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  w.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.9}, {"znear", 0.05}}}}};
  w.add_node({{"camera", 0}, {"translation", {0, 0, 10}}});
  w.doc["materials"] = {
      {{"emissiveFactor", {1, 0.5, 0}}, {"pbrMetallicRoughness", {{"roughnessFactor", 0.3}}}}};
  w.doc["meshes"][0]["primitives"][0]["material"] = 0;
  return w;
}

// A fresh empty directory under the system temp dir.
inline std::filesystem::path fresh_dir(const std::string& name) {
  static int counter = 0;
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      ("voxgi-" + name + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace voxgi::test
