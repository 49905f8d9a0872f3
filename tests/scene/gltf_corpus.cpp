#include "tests/scene/gltf_corpus.hpp"

#include <stb_image_write.h>

#include <cstring>
#include <fstream>

#include "tests/scene/gltf_writer.hpp"

namespace voxgi::test {
namespace {

using nlohmann::json;
using Path = std::filesystem::path;

constexpr int kFloat = 5126, kByte = 5120, kUByte = 5121, kShort = 5122, kUShort = 5123,
              kUInt = 5125;

void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<uint8_t>*>(context);
  const auto* bytes = static_cast<const uint8_t*>(data);
  out->insert(out->end(), bytes, bytes + size);
}

// An 8-bit PNG or JPEG of `components` channels whose texels vary, so filtering shows.
std::vector<uint8_t> image_bytes(int width, int height, int components, bool jpeg = false) {
  std::vector<uint8_t> texels(size_t(width) * size_t(height) * size_t(components));
  for (size_t i = 0; i < texels.size(); ++i) texels[i] = uint8_t(64 + (i * 37) % 160);
  std::vector<uint8_t> out;
  if (jpeg) {
    stbi_write_jpg_to_func(append_bytes, &out, width, height, components, texels.data(), 90);
  } else {
    stbi_write_png_to_func(append_bytes, &out, width, height, components, texels.data(),
                           width * components);
  }
  return out;
}

template <typename T>
std::vector<uint8_t> bytes_of(const std::vector<T>& values) {
  std::vector<uint8_t> out(values.size() * sizeof(T));
  std::memcpy(out.data(), values.data(), out.size());
  return out;
}

// A 2 m floor quad at y = 0 facing +Y, with normals and UVs; more attributes are added by the
// entries. Returns the primitive.
json floor_quad(GltfWriter& w) {
  json p;
  p["attributes"]["POSITION"] = w.add_floats({-1, 0, 1, 1, 0, 1, 1, 0, -1, -1, 0, -1}, "VEC3", 3);
  p["attributes"]["NORMAL"] = w.add_floats({0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0}, "VEC3", 3);
  p["attributes"]["TEXCOORD_0"] = w.add_floats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2", 2);
  p["indices"] = w.add_indices({0, 1, 2, 0, 2, 3});
  return p;
}

// A point light above the origin, so renders of the file have something to shade.
void add_point_light(GltfWriter& w, float range = 0.0f) {
  json light = {{"type", "point"}, {"color", {1, 0.9, 0.8}}, {"intensity", 5}};
  if (range > 0.0f) light["range"] = range;
  w.doc["extensions"]["KHR_lights_punctual"]["lights"].push_back(light);
  const int index = int(w.doc["extensions"]["KHR_lights_punctual"]["lights"].size()) - 1;
  w.add_node({{"translation", {0, 1.5, 0}},
              {"extensions", {{"KHR_lights_punctual", {{"light", index}}}}}});
  w.doc["extensionsUsed"].push_back("KHR_lights_punctual");
}

void use_extension(GltfWriter& w, const std::string& name, bool required) {
  w.doc["extensionsUsed"].push_back(name);
  if (required) w.doc["extensionsRequired"].push_back(name);
}

void write(GltfWriter& w, const Path& path) {
  if (path.extension() == ".glb") {
    w.write_glb(path);
  } else {
    w.write_gltf(path);
  }
}

// A floor with one material and a light; `material` may name textures of the writer.
void floor_scene(GltfWriter& w, const json& material) {
  json p = floor_quad(w);
  p["material"] = 0;
  w.doc["materials"] = json::array({material});
  w.add_mesh_node(p);
  add_point_light(w);
}

GltfCorpusEntry exporter_full_glb() {
  return {"exporter-full.glb",
          "GLB with embedded PNGs; TANGENT, TEXCOORD_1, COLOR_0 (normalized ushort RGBA); "
          "base colour, normal, occlusion on set 1, emissive strength; camera with aspectRatio, "
          "no zfar; extras; double-sided",
          "",
          {},
          [](const Path& path) {
            GltfWriter w;
            w.doc["asset"]["generator"] = "an exporter";
            json p = floor_quad(w);
            p["attributes"]["TANGENT"] =
                w.add_floats({1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1}, "VEC4", 4);
            p["attributes"]["TEXCOORD_1"] =
                w.add_floats({0, 0, 0.5f, 0, 0.5f, 0.5f, 0, 0.5f}, "VEC2", 2);
            p["attributes"]["COLOR_0"] = w.add_accessor(
                std::vector<uint16_t>{65535, 65535, 65535, 65535, 65535, 32768, 32768, 65535, 32768,
                                      65535, 32768, 65535, 32768, 32768, 65535, 65535},
                kUShort, "VEC4", 4, true);
            p["material"] = 0;
            p["extras"] = {{"exporter_id", 7}};
            w.add_mesh_node(p, {{"name", "floor"}, {"extras", {{"layer", "ground"}}}});
            w.add_image(image_bytes(16, 16, 3), "image/png");
            w.add_image(image_bytes(8, 8, 3), "image/png");
            w.add_image(image_bytes(4, 4, 1), "image/png");
            w.doc["textures"] = {{{"source", 0}}, {{"source", 1}}, {{"source", 2}}};
            use_extension(w, "KHR_materials_emissive_strength", false);
            w.doc["materials"] = {
                {{"name", "painted"},
                 {"doubleSided", true},
                 {"pbrMetallicRoughness",
                  {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0}}},
                 {"normalTexture", {{"index", 1}, {"scale", 0.5}}},
                 {"occlusionTexture", {{"index", 2}, {"texCoord", 1}}},
                 {"emissiveFactor", {0.1, 0.05, 0}},
                 {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}}}}}};
            add_point_light(w);
            w.doc["cameras"] = {
                {{"type", "perspective"},
                 {"perspective", {{"yfov", 0.8}, {"znear", 0.05}, {"aspectRatio", 1.5}}}}};
            w.add_node({{"camera", 0}, {"translation", {0, 1, 3}}});
            write(w, path);
          }};
}

GltfCorpusEntry interleaved_glb() {
  return {
      "interleaved.glb",
      "one interleaved vertex view (byteStride 32: POSITION, NORMAL, TEXCOORD_0), uint32 "
      "indices, JPEG texture, KHR_materials_unlit used",
      "",
      {"KHR_materials_unlit"},
      [](const Path& path) {
        GltfWriter w;
        const std::vector<float> vertices = {-1, 0, 1,  0, 1, 0, 0, 1,  //
                                             1,  0, 1,  0, 1, 0, 1, 1,  //
                                             1,  0, -1, 0, 1, 0, 1, 0,  //
                                             -1, 0, -1, 0, 1, 0, 0, 0};
        const int view = w.add_view(bytes_of(vertices), 32);
        const auto accessor = [&](int offset, const char* type) {
          w.doc["accessors"].push_back({{"bufferView", view},
                                        {"byteOffset", offset},
                                        {"componentType", kFloat},
                                        {"type", type},
                                        {"count", 4}});
          return int(w.doc["accessors"].size()) - 1;
        };
        json p;
        p["attributes"]["POSITION"] = accessor(0, "VEC3");
        p["attributes"]["NORMAL"] = accessor(12, "VEC3");
        p["attributes"]["TEXCOORD_0"] = accessor(24, "VEC2");
        w.doc["accessors"][0]["min"] = {-1, 0, -1};
        w.doc["accessors"][0]["max"] = {1, 0, 1};
        p["indices"] = w.add_accessor(std::vector<uint32_t>{0, 1, 2, 0, 2, 3}, kUInt, "SCALAR", 6);
        p["material"] = 0;
        w.add_mesh_node(p);
        w.add_image(image_bytes(32, 16, 3, true), "image/jpeg");
        w.doc["textures"] = {{{"source", 0}}};
        use_extension(w, "KHR_materials_unlit", false);
        w.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
                               {"extensions", {{"KHR_materials_unlit", json::object()}}}}};
        add_point_light(w);
        write(w, path);
      }};
}

GltfCorpusEntry quantized_glb() {
  return {"quantized.glb",
          "KHR_mesh_quantization required: uint16 positions dequantized by the node, int8 "
          "normals (byteStride 4), normalized uint16 UVs with KHR_texture_transform required",
          "",
          {},
          [](const Path& path) {
            GltfWriter w;
            use_extension(w, "KHR_mesh_quantization", true);
            use_extension(w, "KHR_texture_transform", true);
            json p;
            p["attributes"]["POSITION"] = w.add_accessor(
                std::vector<uint16_t>{0, 0, 1000, 0, 1000, 0, 1000, 0, 0, 1000, 0, 0, 0, 0, 0, 0},
                kUShort, "VEC3", 4);
            w.doc["bufferViews"].back()["byteStride"] = 8;
            w.doc["accessors"].back()["min"] = {0, 0, 0};
            w.doc["accessors"].back()["max"] = {1000, 0, 1000};
            p["attributes"]["NORMAL"] = w.add_accessor(
                std::vector<int8_t>{0, 127, 0, 0, 0, 127, 0, 0, 0, 127, 0, 0, 0, 127, 0, 0}, kByte,
                "VEC3", 4, true);
            w.doc["bufferViews"].back()["byteStride"] = 4;
            p["attributes"]["TEXCOORD_0"] =
                w.add_accessor(std::vector<uint16_t>{0, 65535, 65535, 65535, 65535, 0, 0, 0},
                               kUShort, "VEC2", 4, true);
            p["indices"] = w.add_indices({0, 1, 2, 0, 2, 3});
            p["material"] = 0;
            w.add_mesh_node(p, {{"translation", {-1, 0, -1}}, {"scale", {0.002, 1, 0.002}}});
            w.add_image(image_bytes(8, 8, 4), "image/png");
            w.doc["textures"] = {{{"source", 0}}};
            w.doc["materials"] = {
                {{"pbrMetallicRoughness",
                  {{"baseColorTexture",
                    {{"index", 0},
                     {"extensions",
                      {{"KHR_texture_transform", {{"scale", {2, 2}}, {"offset", {0.5, 0}}}}}}}}}}}};
            add_point_light(w);
            write(w, path);
          }};
}

// An extension the file requires and voxgi cannot decode: refused, naming it.
GltfCorpusEntry required_extension(const std::string& file, const std::string& extension,
                                   const std::string& features,
                                   const std::function<void(GltfWriter&)>& decorate) {
  return {file, features, extension, {}, [extension, decorate](const Path& path) {
            GltfWriter w;
            floor_scene(w, {{"pbrMetallicRoughness", {{"roughnessFactor", 0.7}}}});
            use_extension(w, extension, true);
            decorate(w);
            write(w, path);
          }};
}

// The same extension used with an uncompressed fallback (glTF 2.0, 3.12): a warning.
GltfCorpusEntry fallback_extension(const std::string& file, const std::string& extension,
                                   const std::string& features,
                                   const std::function<void(GltfWriter&)>& decorate) {
  return {file, features, "", {extension}, [extension, decorate](const Path& path) {
            GltfWriter w;
            floor_scene(w, {{"pbrMetallicRoughness", {{"roughnessFactor", 0.7}}}});
            use_extension(w, extension, false);
            decorate(w);
            write(w, path);
          }};
}

void draco_primitive(GltfWriter& w) {
  w.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"] = {
      {"bufferView", 0}, {"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}};
}

void meshopt_view(GltfWriter& w) {
  w.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"] = {
      {"buffer", 0}, {"byteLength", 48}, {"byteStride", 12}, {"count", 4}, {"mode", "ATTRIBUTES"}};
}

void basisu_texture(GltfWriter& w) {
  w.doc["images"] = {{{"uri", "texture.ktx2"}, {"mimeType", "image/ktx2"}}};
  w.doc["textures"] = {{{"extensions", {{"KHR_texture_basisu", {{"source", 0}}}}}}};
  w.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
}

// A WebP image with a PNG fallback as `source`; the .webp file holds bytes nothing decodes.
void webp_texture(GltfWriter& w, const Path& folder) {
  w.add_image(image_bytes(4, 4, 3), "image/png");
  w.doc["images"].push_back({{"uri", "texture.webp"}, {"mimeType", "image/webp"}});
  std::ofstream(folder / "texture.webp", std::ios::binary) << "RIFF....WEBPVP8 not decodable";
  w.doc["textures"] = {{{"source", 0}, {"extensions", {{"EXT_texture_webp", {{"source", 1}}}}}}};
  w.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
}

GltfCorpusEntry data_uris() {
  return {
      "data-uris.gltf", "buffer and PNG image as base64 data URIs", "", {}, [](const Path& path) {
        GltfWriter w;
        floor_scene(w, {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}});
        w.doc["images"] = {{{"uri", "data:image/png;base64," + base64(image_bytes(5, 3, 3))}}};
        w.doc["textures"] = {{{"source", 0}}};
        w.doc["buffers"] = {{{"byteLength", w.bin.size()},
                             {"uri", "data:application/octet-stream;base64," + base64(w.bin)}}};
        std::ofstream(path) << w.doc.dump(1);
      }};
}

GltfCorpusEntry sparse_without_view() {
  return {"sparse-without-view.gltf",
          "POSITION accessor with no bufferView (zeros) made a quad by sparse substitution",
          "",
          {},
          [](const Path& path) {
            GltfWriter w;
            json p = floor_quad(w);
            const int indices = w.add_view(bytes_of(std::vector<uint16_t>{0, 1, 2, 3}));
            const int values =
                w.add_view(bytes_of(std::vector<float>{-1, 0, 1, 1, 0, 1, 1, 0, -1, -1, 0, -1}));
            w.doc["accessors"].push_back(
                {{"componentType", kFloat},
                 {"type", "VEC3"},
                 {"count", 4},
                 {"min", {-1, 0, -1}},
                 {"max", {1, 0, 1}},
                 {"sparse",
                  {{"count", 4},
                   {"indices", {{"bufferView", indices}, {"componentType", kUShort}}},
                   {"values", {{"bufferView", values}}}}}});
            p["attributes"]["POSITION"] = int(w.doc["accessors"].size()) - 1;
            w.add_mesh_node(p);
            add_point_light(w);
            write(w, path);
          }};
}

GltfCorpusEntry texture_formats() {
  return {
      "texture-formats.gltf",
      "16-bit grey PNG, 1-channel 3×5 (non power of two), grey+alpha, RGB JPEG; "
      "clamp-to-edge and mirrored-repeat samplers",
      "",
      {"MIRRORED_REPEAT"},
      [](const Path& path) {
        const Path folder = path.parent_path();
        const std::vector<uint8_t> deep = sixteen_bit_grey_png();
        std::ofstream(folder / "deep.png", std::ios::binary)
            .write(reinterpret_cast<const char*>(deep.data()), std::streamsize(deep.size()));
        for (const auto& [name, bytes] : {std::pair{"grey.png", image_bytes(3, 5, 1)},
                                          std::pair{"grey-alpha.png", image_bytes(6, 6, 2)},
                                          std::pair{"colour.jpg", image_bytes(9, 7, 3, true)}}) {
          std::ofstream(folder / name, std::ios::binary)
              .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        }
        GltfWriter w;
        w.doc["images"] = {{{"uri", "deep.png"}},
                           {{"uri", "grey.png"}},
                           {{"uri", "grey-alpha.png"}},
                           {{"uri", "colour.jpg"}}};
        w.doc["samplers"] = {{{"wrapS", 33071}, {"wrapT", 33071}},
                             {{"wrapS", 33648}, {"wrapT", 10497}}};
        w.doc["textures"] = {{{"source", 0}},
                             {{"source", 1}, {"sampler", 0}},
                             {{"source", 2}, {"sampler", 1}},
                             {{"source", 3}}};
        floor_scene(
            w,
            {{"alphaMode", "MASK"},
             {"pbrMetallicRoughness",
              {{"baseColorTexture", {{"index", 2}}}, {"metallicRoughnessTexture", {{"index", 0}}}}},
             {"occlusionTexture", {{"index", 1}}},
             {"emissiveTexture", {{"index", 3}}},
             {"emissiveFactor", {0.2, 0.2, 0.2}}});
        write(w, path);
      }};
}

GltfCorpusEntry index_types() {
  return {"index-types.gltf",
          "uint8, uint16 and uint32 indices; a 256×256 grid (131072 triangles) with uint32",
          "",
          {},
          [](const Path& path) {
            GltfWriter w;
            json small = floor_quad(w);
            small["indices"] =
                w.add_accessor(std::vector<uint8_t>{0, 1, 2, 0, 2, 3}, kUByte, "SCALAR", 6);
            w.add_mesh_node(small);
            const int n = 257;
            std::vector<float> positions;
            std::vector<uint32_t> indices;
            for (int z = 0; z < n; ++z) {
              for (int x = 0; x < n; ++x) {
                positions.insert(positions.end(),
                                 {float(x) / (n - 1) * 2 - 1, 0.3f * float((x + z) % 2),
                                  float(z) / (n - 1) * 2 - 1});
              }
            }
            for (int z = 0; z + 1 < n; ++z) {
              for (int x = 0; x + 1 < n; ++x) {
                const uint32_t i = uint32_t(z * n + x);
                indices.insert(indices.end(), {i, i + uint32_t(n), i + 1, i + 1, i + uint32_t(n),
                                               i + uint32_t(n) + 1});
              }
            }
            json grid;
            grid["attributes"]["POSITION"] = w.add_floats(positions, "VEC3", 3);
            grid["indices"] = w.add_accessor(indices, kUInt, "SCALAR", indices.size());
            w.add_mesh_node(grid, {{"translation", {0, -0.5, 0}}});
            add_point_light(w);
            write(w, path);
          }};
}

GltfCorpusEntry strips_and_fans() {
  return {"strips-fans-points-lines.gltf",
          "TRIANGLE_STRIP and TRIANGLE_FAN (drawn), POINTS and LINES (no surface: skipped)",
          "",
          {"primitives[2].mode", "primitives[3].mode"},
          [](const Path& path) {
            GltfWriter w;
            const int positions =
                w.add_floats({-1, 0, 1, 1, 0, 1, -1, 0, -1, 1, 0, -1, 0, 0.5f, -1.5f}, "VEC3", 3);
            json strip = {{"attributes", {{"POSITION", positions}}}, {"mode", 5}};
            json fan = {{"attributes", {{"POSITION", positions}}},
                        {"indices", w.add_indices({0, 1, 3, 2})},
                        {"mode", 6}};
            json points = {{"attributes", {{"POSITION", positions}}}, {"mode", 0}};
            json lines = {{"attributes", {{"POSITION", positions}}}, {"mode", 1}};
            w.doc["meshes"].push_back({{"primitives", {strip, fan, points, lines}}});
            w.add_node({{"mesh", 0}});
            add_point_light(w);
            write(w, path);
          }};
}

GltfCorpusEntry skinned() {
  return {
      "skinned.gltf",
      "skin with two joints, inverseBindMatrices, JOINTS_0 (ubyte) and WEIGHTS_0, a joint "
      "animation",
      "",
      {"skin"},
      [](const Path& path) {
        GltfWriter w;
        json p = floor_quad(w);
        p["attributes"]["JOINTS_0"] =
            w.add_accessor(std::vector<uint8_t>{0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0},
                           kUByte, "VEC4", 4);
        p["attributes"]["WEIGHTS_0"] =
            w.add_floats({1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 0, 1, 0, 0, 0.5f, 0.5f, 0, 0}, "VEC4", 4);
        const int root = w.add_node({{"name", "root"}, {"children", {1}}});
        w.add_node({{"name", "tip"}, {"translation", {0, 0, -1}}}, false);
        const std::vector<float> identity_then_back = {
            1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,  //
            1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1};
        w.doc["skins"] = {{{"joints", {root, 1}},
                           {"skeleton", root},
                           {"inverseBindMatrices", w.add_floats(identity_then_back, "MAT4", 16)}}};
        w.add_mesh_node(p, {{"skin", 0}});
        const int times = w.add_floats({0, 1}, "SCALAR", 1);
        const int rotations = w.add_floats({0, 0, 0, 1, 0.3826834f, 0, 0, 0.9238795f}, "VEC4", 4);
        w.doc["animations"] = {
            {{"samplers", {{{"input", times}, {"output", rotations}}}},
             {"channels", {{{"sampler", 0}, {"target", {{"node", 1}, {"path", "rotation"}}}}}}}};
        add_point_light(w);
        write(w, path);
      }};
}

GltfCorpusEntry morph_targets() {
  return {
      "morph-targets.gltf",
      "two morph targets, mesh weights and a weights animation",
      "",
      {"targets", "weights"},
      [](const Path& path) {
        GltfWriter w;
        json p = floor_quad(w);
        const int up = w.add_floats({0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC3", 3);
        const int side = w.add_floats({0, 0, 0, 0.5f, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC3", 3);
        p["targets"] = {{{"POSITION", up}}, {{"POSITION", side}}};
        w.doc["meshes"].push_back({{"primitives", {p}}, {"weights", {0.5, 0.25}}});
        const int node = w.add_node({{"mesh", 0}});
        const int times = w.add_floats({0, 1}, "SCALAR", 1);
        const int weights = w.add_floats({0, 0, 1, 1}, "SCALAR", 1);
        w.doc["animations"] = {
            {{"samplers", {{{"input", times}, {"output", weights}}}},
             {"channels", {{{"sampler", 0}, {"target", {{"node", node}, {"path", "weights"}}}}}}}};
        add_point_light(w);
        write(w, path);
      }};
}

GltfCorpusEntry cameras() {
  return {"cameras.gltf",
          "perspective camera with aspectRatio 2 and no zfar under a mirrored parent; an "
          "orthographic camera (not supported: skipped)",
          "",
          {"orthographic"},
          [](const Path& path) {
            GltfWriter w;
            floor_scene(w, {{"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}});
            w.doc["cameras"] = {
                {{"type", "perspective"},
                 {"perspective", {{"yfov", 0.7}, {"znear", 0.1}, {"aspectRatio", 2.0}}}},
                {{"type", "orthographic"},
                 {"orthographic", {{"xmag", 2}, {"ymag", 2}, {"znear", 0.1}, {"zfar", 20}}}}};
            const int camera = w.add_node({{"camera", 0}, {"translation", {0, 1, 4}}}, false);
            w.add_node({{"scale", {-1, 1, 1}}, {"children", {camera}}});
            w.add_node({{"camera", 1}, {"translation", {0, 5, 0}}});
            write(w, path);
          }};
}

GltfCorpusEntry scenes(bool default_scene) {
  return {default_scene ? "second-scene.gltf" : "no-default-scene.gltf",
          default_scene ? "two scenes, \"scene\": 1 shows the second"
                        : "no \"scene\" property: the first scene is shown",
          "",
          {},
          [default_scene](const Path& path) {
            GltfWriter w;
            floor_scene(w, {{"pbrMetallicRoughness", {{"roughnessFactor", 0.4}}}});
            w.doc["scenes"].push_back({{"nodes", {0}}, {"name", "floor only"}});
            if (default_scene) {
              w.doc["scene"] = 1;
            } else {
              w.doc.erase("scene");
            }
            write(w, path);
          }};
}

GltfCorpusEntry empty() {
  return {"empty.gltf", "asset only: no scene, node, mesh or light", "", {}, [](const Path& path) {
            std::ofstream(path) << R"({"asset": {"version": "2.0"}})";
          }};
}

GltfCorpusEntry alpha_modes() {
  return {"alpha-modes.gltf",
          "MASK with alphaCutoff 0.3 from a texture's alpha; BLEND with vertex-colour alpha",
          "",
          {},
          [](const Path& path) {
            GltfWriter w;
            json masked = floor_quad(w);
            masked["material"] = 0;
            json blended = floor_quad(w);
            blended["attributes"]["COLOR_0"] = w.add_floats(
                {1, 1, 1, 0.2f, 1, 0.5f, 0.5f, 0.8f, 1, 1, 1, 0.5f, 0.5f, 0.5f, 1, 1}, "VEC4", 4);
            blended["material"] = 1;
            w.add_mesh_node(masked);
            w.add_mesh_node(blended, {{"translation", {0, 0.5, 0}}});
            w.add_image(image_bytes(8, 8, 4), "image/png");
            w.doc["textures"] = {{{"source", 0}}};
            w.doc["materials"] = {
                {{"alphaMode", "MASK"},
                 {"alphaCutoff", 0.3},
                 {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}},
                {{"alphaMode", "BLEND"}, {"doubleSided", true}}};
            add_point_light(w);
            write(w, path);
          }};
}

GltfCorpusEntry lights() {
  return {"lights.gltf",
          "directional, spot (inner and outer cone) and point light with range; an emissive "
          "material with emissive strength 10",
          "",
          {},
          [](const Path& path) {
            GltfWriter w;
            use_extension(w, "KHR_materials_emissive_strength", false);
            floor_scene(w, {{"emissiveFactor", {1, 0.5, 0.25}},
                            {"extensions",
                             {{"KHR_materials_emissive_strength", {{"emissiveStrength", 10}}}}}});
            auto& list = w.doc["extensions"]["KHR_lights_punctual"]["lights"];
            list.push_back({{"type", "directional"}, {"intensity", 3}});
            list.push_back({{"type", "spot"},
                            {"intensity", 20},
                            {"range", 6},
                            {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.6}}}});
            w.add_node({{"rotation", {-0.3826834, 0, 0, 0.9238795}},
                        {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
            w.add_node({{"translation", {0.5, 2, 0}},
                        {"rotation", {-0.7071068, 0, 0, 0.7071068}},
                        {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
            w.doc["extensions"]["KHR_lights_punctual"]["lights"][0]["range"] = 3;
            write(w, path);
          }};
}

GltfCorpusEntry material_extensions() {
  return {"material-extensions.gltf",
          "KHR_materials_clearcoat, transmission, volume, ior, specular, sheen and variants "
          "used (metallic-roughness drawn)",
          "",
          {"KHR_materials_clearcoat", "KHR_materials_variants"},
          [](const Path& path) {
            GltfWriter w;
            json extensions;
            for (const char* name :
                 {"KHR_materials_clearcoat", "KHR_materials_transmission", "KHR_materials_volume",
                  "KHR_materials_ior", "KHR_materials_specular", "KHR_materials_sheen"}) {
              use_extension(w, name, false);
              extensions[name] = json::object();
            }
            use_extension(w, "KHR_materials_variants", false);
            w.doc["extensions"]["KHR_materials_variants"] = {
                {"variants", {{{"name", "red"}}, {{"name", "blue"}}}}};
            floor_scene(w, {{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.2, 0.2, 1}}}},
                            {"extensions", extensions}});
            w.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"] = {
                {"mappings", {{{"material", 0}, {"variants", {0, 1}}}}}};
            write(w, path);
          }};
}

GltfCorpusEntry texture_transforms() {
  return {"texture-transforms.gltf",
          "KHR_texture_transform on all five slots (offset, rotation, scale), two on "
          "TEXCOORD_1 by the extension's texCoord",
          "",
          {},
          [](const Path& path) {
            GltfWriter w;
            use_extension(w, "KHR_texture_transform", false);
            json p = floor_quad(w);
            p["attributes"]["TEXCOORD_1"] =
                w.add_floats({0.2f, 0.2f, 0.8f, 0.2f, 0.8f, 0.8f, 0.2f, 0.8f}, "VEC2", 2);
            p["material"] = 0;
            w.add_mesh_node(p);
            w.add_image(image_bytes(16, 16, 4), "image/png");
            w.doc["textures"] = {{{"source", 0}}};
            const auto slot = [](double rotation, int tex_coord) {
              return json{{"index", 0},
                          {"extensions",
                           {{"KHR_texture_transform",
                             {{"offset", {0.25, 0.5}},
                              {"rotation", rotation},
                              {"scale", {3, 0.5}},
                              {"texCoord", tex_coord}}}}}};
            };
            w.doc["materials"] = {{{"pbrMetallicRoughness",
                                    {{"baseColorTexture", slot(0.3, 0)},
                                     {"metallicRoughnessTexture", slot(-1.0, 1)}}},
                                   {"normalTexture", slot(3.14159, 0)},
                                   {"occlusionTexture", slot(0.0, 1)},
                                   {"emissiveTexture", slot(1.0, 0)},
                                   {"emissiveFactor", {0.5, 0.5, 0.5}}}};
            add_point_light(w);
            write(w, path);
          }};
}

GltfCorpusEntry mirrored() {
  return {"mirrored.glb",
          "negative scales: a mirrored instance, a doubly mirrored one and a flattened one (scale "
          "0 on one axis)",
          "",
          {},
          [](const Path& path) {
            GltfWriter w;
            floor_scene(w, {{"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.8, 0.2, 1}}}}});
            w.add_node({{"mesh", 0}, {"scale", {-1, 1, 1}}, {"translation", {0, 0.5, 0}}});
            w.add_node({{"mesh", 0}, {"scale", {-1, -1, 1}}, {"translation", {0, 1, 0}}});
            w.add_node({{"mesh", 0}, {"scale", {1, 0, 1}}, {"translation", {0, 0.2, 0}}});
            write(w, path);
          }};
}

GltfCorpusEntry gpu_instancing() {
  return {"gpu-instancing.gltf",
          "EXT_mesh_gpu_instancing required: 16 instances of a quad with float TRANSLATION, "
          "normalized short ROTATION and SCALE",
          "",
          {},
          [](const Path& path) {
            GltfWriter w;
            floor_scene(w, {{"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 0.6, 0.3, 1}}}}});
            use_extension(w, "EXT_mesh_gpu_instancing", true);
            std::vector<float> translations, scales;
            std::vector<int16_t> rotations;
            for (int i = 0; i < 16; ++i) {
              translations.insert(translations.end(),
                                  {float(i % 4) - 1.5f, 0.1f * float(i), float(i / 4) - 1.5f});
              scales.insert(scales.end(), {0.2f, 1.0f, 0.2f});
              rotations.insert(rotations.end(), {0, int16_t(i * 2000), 0, 32767});
            }
            json attributes = {{"TRANSLATION", w.add_floats(translations, "VEC3", 3)},
                               {"ROTATION", w.add_accessor(rotations, kShort, "VEC4", 16, true)},
                               {"SCALE", w.add_floats(scales, "VEC3", 3)}};
            w.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = attributes;
            write(w, path);
          }};
}

}  // namespace

std::vector<GltfCorpusEntry> gltf_corpus() {
  std::vector<GltfCorpusEntry> corpus = {exporter_full_glb(), interleaved_glb(), quantized_glb()};
  corpus.push_back(required_extension("draco-required.gltf", "KHR_draco_mesh_compression",
                                      "Draco-compressed primitive, extension required",
                                      draco_primitive));
  corpus.push_back(fallback_extension("draco-with-fallback.gltf", "KHR_draco_mesh_compression",
                                      "Draco primitive with uncompressed attributes, extension "
                                      "only used",
                                      draco_primitive));
  corpus.push_back(required_extension("meshopt-required.glb", "EXT_meshopt_compression",
                                      "meshopt-compressed buffer view, extension required",
                                      meshopt_view));
  corpus.push_back(fallback_extension("meshopt-with-fallback.glb", "EXT_meshopt_compression",
                                      "meshopt buffer view with its uncompressed data, "
                                      "extension only used",
                                      meshopt_view));
  corpus.push_back(required_extension("ktx2-required.gltf", "KHR_texture_basisu",
                                      "KTX2/Basis texture with no fallback, extension required",
                                      basisu_texture));
  corpus.push_back({"webp-with-png-fallback.gltf",
                    "EXT_texture_webp texture with a PNG fallback source, extension only used",
                    "",
                    {"EXT_texture_webp"},
                    [](const Path& path) {
                      GltfWriter w;
                      floor_scene(w, {{"pbrMetallicRoughness", {{"roughnessFactor", 0.7}}}});
                      use_extension(w, "EXT_texture_webp", false);
                      webp_texture(w, path.parent_path());
                      write(w, path);
                    }});
  corpus.push_back(required_extension("webp-required.gltf", "EXT_texture_webp",
                                      "WebP texture, extension required", [](GltfWriter&) {}));
  corpus.push_back(required_extension(
      "spec-gloss-required.gltf", "KHR_materials_pbrSpecularGlossiness",
      "specular-glossiness materials (archived extension), required", [](GltfWriter&) {}));
  for (GltfCorpusEntry entry :
       {data_uris(), sparse_without_view(), texture_formats(), index_types(), strips_and_fans(),
        skinned(), morph_targets(), cameras(), scenes(true), scenes(false), empty(), alpha_modes(),
        lights(), material_extensions(), texture_transforms(), mirrored(), gpu_instancing()}) {
    corpus.push_back(std::move(entry));
  }
  return corpus;
}

}  // namespace voxgi::test
