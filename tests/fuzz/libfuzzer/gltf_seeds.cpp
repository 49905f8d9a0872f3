// Writes the seed corpus of voxgi_fuzz_gltf into OUT_DIR: small documents built with the
// tests' GltfWriter (a node hierarchy, cameras, the three light types, materials with textures
// and KHR extensions, a sparse accessor, an animation), each as .gltf with its buffer inside
// (a data URI, since the fuzzer writes one file) and as .glb; and, with SCENES_DIR, every
// .gltf under it with its buffer and image files made data URIs, and every .glb: as it is up to
// 1 MiB, larger ones as their JSON chunk alone (a .gltf whose buffer has no URI, read as zeros):
// a real scene's structure at a size the fuzzer mutates quickly.
//
//   voxgi_fuzz_gltf_seeds OUT_DIR [SCENES_DIR]

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/scene/gltf_writer.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using voxgi::test::base64;
using voxgi::test::GltfWriter;
using voxgi::test::hierarchy_document;
using voxgi::test::sixteen_bit_grey_png;

// A 1 x 1 RGBA PNG and a 2 x 1 16-bit grey PNG.
constexpr const char* kPng8 =
    "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mNkYPhfDwAChwGA"
    "60e6kgAAAABJRU5ErkJggg==";
const std::vector<uint8_t> kPng16 = sixteen_bit_grey_png();

std::vector<uint8_t> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// `w` as <name>.glb and as <name>.gltf with the buffer as a data URI.
void write_both(GltfWriter& w, const fs::path& out, const std::string& name) {
  w.write_glb(out / (name + ".glb"));
  if (!w.bin.empty()) {
    w.doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(w.bin);
  }
  write_text(out / (name + ".gltf"), w.doc.dump(1));
}

void triangle(const fs::path& out) {
  GltfWriter w;
  w.add_mesh_node(w.triangle(false));
  write_both(w, out, "triangle");
}

// The input tests' document: hierarchy, camera, light, material, indices.
void hierarchy(const fs::path& out) {
  GltfWriter w = hierarchy_document();
  write_both(w, out, "hierarchy");
}

// Textures (8- and 16-bit PNG, a sampler, KHR_texture_transform), emissive strength, every
// light type, a matrix node, a named camera with zfar and an aspect ratio.
void materials(const fs::path& out) {
  GltfWriter w;
  json p = w.triangle();
  p["material"] = 0;
  w.add_mesh_node(p, {{"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.5, 0, 0, 1}}});
  const int tangents = w.add_floats({1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1}, "VEC4", 4);
  w.doc["meshes"][0]["primitives"][0]["attributes"]["TANGENT"] = tangents;
  w.doc["images"] = {{{"uri", kPng8}}, {{"uri", "data:image/png;base64," + base64(kPng16)}}};
  w.doc["samplers"] = {{{"wrapS", 33071}, {"wrapT", 33648}, {"magFilter", 9728}}};
  w.doc["textures"] = {{{"source", 0}, {"sampler", 0}}, {{"source", 1}}};
  json transform = {{"offset", {0.5, 0}}, {"rotation", 0.3}, {"scale", {2, 2}}, {"texCoord", 0}};
  w.doc["materials"] = {
      {{"name", "textured"},
       {"pbrMetallicRoughness",
        {{"baseColorFactor", {1, 0.8, 0.6, 1}},
         {"baseColorTexture",
          {{"index", 0}, {"extensions", {{"KHR_texture_transform", transform}}}}},
         {"metallicRoughnessTexture", {{"index", 1}}},
         {"metallicFactor", 0.5}}},
       {"normalTexture", {{"index", 0}, {"scale", 0.5}}},
       {"occlusionTexture", {{"index", 1}, {"strength", 0.5}}},
       {"emissiveTexture", {{"index", 0}}},
       {"emissiveFactor", {1, 1, 1}},
       {"alphaMode", "MASK"},
       {"alphaCutoff", 0.4},
       {"doubleSided", true},
       {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}}}}}};
  w.doc["extensionsUsed"] = {"KHR_lights_punctual", "KHR_materials_emissive_strength",
                             "KHR_texture_transform"};
  w.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "spot"},
       {"color", {1, 0.9, 0.8}},
       {"intensity", 50},
       {"range", 20},
       {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.6}}}},
      {{"type", "directional"}, {"intensity", 3}}};
  w.add_node({{"rotation", {0, 0, 0.3826834, 0.9238795}},
              {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  w.add_node({{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
  w.doc["cameras"] = {
      {{"name", "main"},
       {"type", "perspective"},
       {"perspective", {{"yfov", 0.7}, {"znear", 0.1}, {"zfar", 100}, {"aspectRatio", 1.5}}}}};
  w.add_node({{"camera", 0}, {"translation", {0, 1, 5}}});
  write_both(w, out, "materials");
}

// 32-bit indices, a sparse accessor over the positions, normalized UVs, a second scene.
void accessors(const fs::path& out) {
  GltfWriter w;
  json p;
  p["attributes"]["POSITION"] = w.add_floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, "VEC3", 3);
  p["attributes"]["TEXCOORD_0"] =
      w.add_accessor<uint16_t>({0, 0, 65535, 0, 0, 65535, 65535, 65535}, 5123, "VEC2", 4, true);
  p["indices"] = w.add_accessor<uint32_t>({0, 1, 2, 2, 1, 3}, 5125, "SCALAR", 6);
  p["mode"] = 4;
  const int sparse_indices = w.add_accessor<uint16_t>({3, 0}, 5123, "SCALAR", 1);
  const int sparse_values = w.add_floats({2, 2, 0}, "VEC3", 3);
  w.doc["accessors"][int(p["attributes"]["POSITION"])]["sparse"] = {
      {"count", 1},
      {"indices",
       {{"bufferView", w.doc["accessors"][sparse_indices]["bufferView"]}, {"componentType", 5123}}},
      {"values", {{"bufferView", w.doc["accessors"][sparse_values]["bufferView"]}}}};
  w.doc["accessors"][int(p["attributes"]["POSITION"])]["min"] = {0, 0, 0};
  w.doc["accessors"][int(p["attributes"]["POSITION"])]["max"] = {2, 2, 0};
  w.add_mesh_node(p);
  json lines = {{"attributes", {{"POSITION", p["attributes"]["POSITION"]}}}, {"mode", 1}};
  w.add_mesh_node(lines);
  w.doc["scenes"].push_back({{"nodes", {0}}});
  write_both(w, out, "accessors");
}

// A translation, rotation and scale animation with linear, step and cubic spline samplers.
void animation(const fs::path& out) {
  GltfWriter w;
  const int node = w.add_mesh_node(w.triangle());
  const int input = w.add_floats({0, 1}, "SCALAR", 1);
  const int translation = w.add_floats({0, 0, 0, 4, 0, 0}, "VEC3", 3);
  const int rotation = w.add_floats({0, 0, 0, 1, 0, 0.7071068f, 0, 0.7071068f}, "VEC4", 4);
  const int spline =
      w.add_floats({0, 0, 0, 1, 1, 1, 0, 0, 0, 0, 0, 0, 2, 2, 2, 0, 0, 0}, "VEC3", 3);
  w.doc["animations"] = {
      {{"name", "move"},
       {"channels",
        {{{"sampler", 0}, {"target", {{"node", node}, {"path", "translation"}}}},
         {{"sampler", 1}, {"target", {{"node", node}, {"path", "rotation"}}}},
         {{"sampler", 2}, {"target", {{"node", node}, {"path", "scale"}}}}}},
       {"samplers",
        {{{"input", input}, {"output", translation}},
         {{"input", input}, {"output", rotation}, {"interpolation", "STEP"}},
         {{"input", input}, {"output", spline}, {"interpolation", "CUBICSPLINE"}}}}}};
  write_both(w, out, "animation");
}

// The JSON chunk of a GLB (empty when it has none).
std::string glb_json(const std::vector<uint8_t>& bytes) {
  if (bytes.size() < 20) return {};
  uint32_t length = 0, type = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  std::memcpy(&type, bytes.data() + 16, 4);
  if (type != 0x4E4F534A || length > bytes.size() - 20) return {};
  return std::string(bytes.begin() + 20, bytes.begin() + 20 + length);
}

// A .gltf of the shared scenes with its buffers and images inside as data URIs.
void embed(const fs::path& gltf, const fs::path& out_file) {
  json doc = json::parse(std::ifstream(gltf));
  for (const char* list : {"buffers", "images"}) {
    if (!doc.contains(list)) continue;
    for (json& item : doc[list]) {
      if (!item.contains("uri") || item["uri"].get<std::string>().rfind("data:", 0) == 0) continue;
      const std::vector<uint8_t> bytes =
          read_bytes(gltf.parent_path() / item["uri"].get<std::string>());
      item["uri"] = "data:application/octet-stream;base64," + base64(bytes);
    }
  }
  write_text(out_file, doc.dump());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: %s OUT_DIR [SCENES_DIR]\n", argv[0]);
    return 2;
  }
  try {
    const fs::path out = argv[1];
    fs::create_directories(out);
    triangle(out);
    hierarchy(out);
    materials(out);
    accessors(out);
    animation(out);
    if (argc == 3) {
      for (const auto& entry : fs::recursive_directory_iterator(argv[2])) {
        if (!entry.is_regular_file()) continue;
        const fs::path& path = entry.path();
        const std::string name = "shared-" + path.stem().string() + path.extension().string();
        if (path.extension() == ".glb" && fs::file_size(path) <= (1u << 20)) {
          fs::copy_file(path, out / name, fs::copy_options::overwrite_existing);
        } else if (path.extension() == ".glb") {
          const std::string text = glb_json(read_bytes(path));
          if (!text.empty()) write_text(out / ("shared-" + path.stem().string() + ".gltf"), text);
        }
        if (path.extension() == ".gltf") embed(path, out / name);
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "voxgi_fuzz_gltf_seeds: %s\n", e.what());
    return 1;
  }
  return 0;
}
