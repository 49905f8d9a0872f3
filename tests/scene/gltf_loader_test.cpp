#include <gtest/gtest.h>
#include <stb_image_write.h>

#include <cmath>
#include <fstream>

#include "engine/scene/gltf_loader.hpp"
#include "tests/scene/gltf_writer.hpp"

namespace voxgi::scene {
namespace {

using nlohmann::json;
using test::GltfWriter;

// The SceneError message of loading `path`, or "" when it loaded.
std::string load_error(const std::filesystem::path& path) {
  try {
    load_gltf(path);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

bool any_warning(const Scene& scene, const std::string& part) {
  for (const std::string& w : scene.warnings) {
    if (contains(w, part)) return true;
  }
  return false;
}

class GltfLoader : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_dir("gltf"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(GltfLoader, TriangleWithHierarchyLightsAndCamera) {
  GltfWriter w;
  const int child = w.add_node({{"name", "child"}, {"translation", {0, 0, -1}}}, false);
  w.doc["meshes"].push_back({{"primitives", json::array({w.triangle()})}});
  w.doc["nodes"][child]["mesh"] = 0;
  w.add_node({{"name", "parent"}, {"children", {child}}, {"translation", {1, 2, 3}}});
  // A matrix node: translation by (5, 0, 0).
  w.add_node({{"name", "matrix"},
              {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1}},
              {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  w.doc["extensionsUsed"] = {"KHR_lights_punctual", "KHR_materials_emissive_strength"};
  w.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "spot"},
       {"color", {1, 0.5, 0.25}},
       {"intensity", 20},
       {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}}};
  w.doc["cameras"] = {{{"type", "perspective"},
                       {"name", "cam"},
                       {"perspective", {{"yfov", 0.9}, {"znear", 0.05}}}}};
  w.add_node({{"camera", 0}, {"translation", {0, 0, 10}}});
  w.doc["materials"] = {
      {{"name", "glow"},
       {"emissiveFactor", {1, 0.5, 0}},
       {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 8}}}}},
       {"pbrMetallicRoughness", {{"roughnessFactor", 0.3}, {"metallicFactor", 0}}}}};
  w.doc["meshes"][0]["primitives"][0]["material"] = 0;
  w.write_gltf(dir_ / "scene.gltf");

  const Scene scene = load_gltf(dir_ / "scene.gltf");
  EXPECT_TRUE(scene.warnings.empty()) << scene.warnings[0];
  ASSERT_EQ(scene.meshes.size(), 1u);
  const auto instances = scene.instances();
  ASSERT_EQ(instances.size(), 1u);
  EXPECT_EQ(glm::vec3(instances[0].world[3]), glm::vec3(1, 2, 2));
  const Primitive& p = scene.meshes[0].primitives[0];
  EXPECT_EQ(p.vertices.size(), 3u);
  EXPECT_EQ(p.vertices[1].uv, glm::vec2(1, 0));
  EXPECT_NEAR(p.vertices[0].tangent.x, 1.0f, 1e-6f);  // generated from the UVs
  EXPECT_EQ(scene.materials[0].emissive, glm::vec3(8, 4, 0));
  EXPECT_NEAR(scene.materials[0].roughness, 0.3f, 1e-6f);
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].type, LightType::Spot);
  EXPECT_EQ(scene.lights[0].position, glm::vec3(5, 0, 0));
  EXPECT_EQ(scene.lights[0].direction, glm::vec3(0, 0, -1));
  EXPECT_NEAR(scene.lights[0].outer_cone, 0.5f, 1e-6f);
  ASSERT_EQ(scene.cameras.size(), 1u);
  EXPECT_EQ(scene.cameras[0].name, "cam");
  EXPECT_GT(scene.cameras[0].zfar, 10.0f);  // infinite → from the bounds
  const SceneFeatures f = scene.features();
  EXPECT_TRUE(f.has_emissive);
  EXPECT_TRUE(f.has_glossy);
  EXPECT_TRUE(f.has_spot_lights);
}

TEST_F(GltfLoader, NormalizedIntegersNonIndexedAndMissingNormals) {
  GltfWriter w;
  json p;
  p["attributes"]["POSITION"] = w.add_floats({0, 0, 0, 1, 0, 0, 0, 0, -1}, "VEC3", 3);
  p["attributes"]["TEXCOORD_0"] =
      w.add_accessor(std::vector<uint8_t>{0, 0, 255, 0, 0, 255, 0, 0}, 5121, "VEC2", 3, true);
  w.add_mesh_node(p);
  // int16 normalized normals (0, 32767, 0) and uint16 indices on a second primitive.
  json q;
  q["attributes"]["POSITION"] = w.add_floats({0, 0, 0, 1, 0, 0, 0, 0, -1}, "VEC3", 3);
  q["attributes"]["NORMAL"] = w.add_accessor(
      std::vector<int16_t>{0, 32767, 0, 0, 0, 32767, 0, 0, 0, 0, 0, 0}, 5122, "VEC3", 3, true);
  q["indices"] = w.add_indices({0, 1, 2});
  w.add_mesh_node(q);
  w.write_glb(dir_ / "ints.glb");

  const Scene scene = load_gltf(dir_ / "ints.glb");
  const Primitive& a = scene.meshes[0].primitives[0];
  ASSERT_EQ(a.indices.size(), 3u);
  EXPECT_EQ(a.vertices[1].uv, glm::vec2(1, 0));
  for (const Vertex& v : a.vertices) EXPECT_NEAR(v.normal.y, 1.0f, 1e-6f);  // flat, +Y
  const Primitive& b = scene.meshes[1].primitives[0];
  EXPECT_NEAR(b.vertices[0].normal.y, 1.0f, 1e-6f);
  EXPECT_NEAR(b.vertices[1].normal.z, 1.0f, 1e-6f);  // normalized, then row 3 skipped
  // The third normal was zero: repaired from the face (+Y).
  EXPECT_NEAR(b.vertices[2].normal.y, 1.0f, 1e-6f);
}

TEST_F(GltfLoader, UnsupportedFeaturesBecomeWarnings) {
  GltfWriter w;
  w.add_mesh_node(w.triangle());
  json points;
  points["attributes"]["POSITION"] = w.add_floats({0, 0, 0, 1, 1, 1}, "VEC3", 3);
  points["mode"] = 0;
  w.add_mesh_node(points);
  w.doc["extensionsUsed"] = {"KHR_materials_transmission"};
  w.doc["cameras"] = {{{"type", "orthographic"},
                       {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 10}}}}};
  w.add_node({{"camera", 0}});
  // A texture whose image file is missing.
  w.doc["images"] = {{{"uri", "missing.png"}}};
  w.doc["textures"] = {{{"source", 0}}};
  w.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  w.doc["meshes"][0]["primitives"][0]["material"] = 0;
  w.write_gltf(dir_ / "unsupported.gltf");

  const Scene scene = load_gltf(dir_ / "unsupported.gltf");
  EXPECT_TRUE(any_warning(scene, "KHR_materials_transmission"));
  EXPECT_TRUE(any_warning(scene, "meshes[1].primitives[0].mode"));
  EXPECT_TRUE(any_warning(scene, "orthographic"));
  EXPECT_TRUE(any_warning(scene, "textures[0]"));
  EXPECT_EQ(scene.meshes[1].primitives.size(), 0u);
  EXPECT_EQ(scene.cameras.size(), 0u);
  EXPECT_EQ(scene.materials[0].base_color_tex, -1);
  EXPECT_EQ(scene.features().triangle_count, 1u);

  // Required by the file: refused, naming the extension.
  w.doc["extensionsRequired"] = {"KHR_materials_transmission"};
  std::ofstream(dir_ / "unsupported.gltf") << w.doc.dump();
  const std::string message = load_error(dir_ / "unsupported.gltf");
  EXPECT_TRUE(contains(message, (dir_ / "unsupported.gltf").string() +
                                    ": extensionsRequired: unsupported extension "
                                    "KHR_materials_transmission"))
      << message;
}

TEST_F(GltfLoader, TexturesExpandToRgbaAndSplitByColourSpace) {
  // A 3 × 5 grey PNG (1 channel, non power of two) used as base colour and occlusion.
  std::vector<uint8_t> grey(15);
  for (size_t i = 0; i < grey.size(); ++i) grey[i] = uint8_t(i * 10);
  ASSERT_NE(stbi_write_png((dir_ / "grey.png").c_str(), 3, 5, 1, grey.data(), 3), 0);
  // And a corrupt image file.
  std::ofstream(dir_ / "corrupt.png") << "not a png";
  GltfWriter w;
  json p = w.triangle();
  p["material"] = 0;
  w.add_mesh_node(p);
  w.doc["images"] = {{{"uri", "grey.png"}}, {{"uri", "corrupt.png"}}};
  w.doc["samplers"] = {{{"wrapS", 33071}, {"wrapT", 33071}}};
  w.doc["textures"] = {{{"source", 0}, {"sampler", 0}}, {{"source", 1}}};
  w.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
                         {"occlusionTexture", {{"index", 0}, {"strength", 0.5}}},
                         {"normalTexture", {{"index", 1}}}}};
  w.write_gltf(dir_ / "textured.gltf");

  const Scene scene = load_gltf(dir_ / "textured.gltf");
  ASSERT_EQ(scene.textures.size(), 2u);
  const Material& m = scene.materials[0];
  ASSERT_GE(m.base_color_tex, 0);
  ASSERT_GE(m.occlusion_tex, 0);
  EXPECT_NE(m.base_color_tex, m.occlusion_tex);
  EXPECT_EQ(m.normal_tex, -1);  // corrupt image: dropped with a warning
  EXPECT_TRUE(any_warning(scene, "images[1]"));
  const Texture& srgb = scene.textures[size_t(m.base_color_tex)];
  const Texture& linear = scene.textures[size_t(m.occlusion_tex)];
  EXPECT_TRUE(srgb.srgb);
  EXPECT_FALSE(linear.srgb);
  EXPECT_FALSE(srgb.wrap_repeat);
  EXPECT_EQ(srgb.width, 3u);
  EXPECT_EQ(srgb.height, 5u);
  EXPECT_EQ(srgb.channels, 4u);
  EXPECT_EQ(srgb.bits, 8u);
  ASSERT_EQ(srgb.pixels.size(), 3u * 5u * 4u);
  EXPECT_EQ(srgb.pixels[7 * 4 + 0], 70);
  EXPECT_EQ(srgb.pixels[7 * 4 + 2], 70);
  EXPECT_EQ(srgb.pixels[7 * 4 + 3], 255);
  EXPECT_NEAR(m.occlusion_strength, 0.5f, 1e-6f);
  EXPECT_TRUE(scene.features().has_textures);
}

// COLOR_0 in the forms glTF allows (RGB or RGBA; float, normalized unsigned byte or short),
// TEXCOORD_1, and KHR_texture_transform with its own texCoord.
TEST_F(GltfLoader, VertexColoursSecondUvSetAndTextureTransforms) {
  std::vector<uint8_t> white(4, 255);
  ASSERT_NE(stbi_write_png((dir_ / "white.png").c_str(), 2, 2, 1, white.data(), 2), 0);
  GltfWriter w;
  json rgb_bytes = w.triangle();
  rgb_bytes["attributes"]["COLOR_0"] = w.add_accessor(
      std::vector<uint8_t>{255, 0, 0, 0, 0, 255, 0, 0, 0, 0, 255, 0}, 5121, "VEC3", 3, true);
  // Unsigned-byte VEC3 elements are padded to 4 bytes: the writer's view needs a stride.
  w.doc["bufferViews"].back()["byteStride"] = 4;
  rgb_bytes["attributes"]["TEXCOORD_1"] = w.add_floats({0.5f, 0.25f, 1, 1, 0, 0}, "VEC2", 2);
  rgb_bytes["material"] = 0;
  w.add_mesh_node(rgb_bytes);
  json rgba_shorts = w.triangle();
  rgba_shorts["attributes"]["COLOR_0"] = w.add_accessor(
      std::vector<uint16_t>{65535, 32768, 0, 16384, 0, 0, 0, 65535, 65535, 65535, 65535, 0}, 5123,
      "VEC4", 3, true);
  w.add_mesh_node(rgba_shorts);
  json floats = w.triangle();
  floats["attributes"]["COLOR_0"] =
      w.add_floats({0.25f, 0.5f, 0.75f, 1, 2, -1, 0, 0, 0, 0, 0, 0}, "VEC4", 4);
  w.add_mesh_node(floats);
  w.doc["images"] = {{{"uri", "white.png"}}};
  w.doc["textures"] = {{{"source", 0}}};
  w.doc["extensionsUsed"] = {"KHR_texture_transform"};
  w.doc["extensionsRequired"] = {"KHR_texture_transform"};
  const json transform = {{"offset", {0.5, -0.25}},
                          {"rotation", 1.5707963267948966},
                          {"scale", {2, 4}},
                          {"texCoord", 1}};
  w.doc["materials"] = {
      {{"pbrMetallicRoughness",
        {{"baseColorTexture",
          {{"index", 0}, {"extensions", {{"KHR_texture_transform", transform}}}}}}},
       {"occlusionTexture", {{"index", 0}, {"texCoord", 1}}},
       {"emissiveTexture", {{"index", 0}, {"texCoord", 3}}}}};
  w.write_gltf(dir_ / "colours.gltf");

  const Scene scene = load_gltf(dir_ / "colours.gltf");
  const auto& first = scene.meshes[0].primitives[0].vertices;
  EXPECT_EQ(first[0].color, glm::vec4(1, 0, 0, 1));  // RGB: alpha 1
  EXPECT_EQ(first[2].color, glm::vec4(0, 0, 1, 1));
  EXPECT_EQ(first[0].uv1, glm::vec2(0.5f, 0.25f));
  const auto& second = scene.meshes[1].primitives[0].vertices;
  EXPECT_NEAR(second[0].color.y, 32768.0f / 65535.0f, 1e-6f);
  EXPECT_NEAR(second[0].color.w, 16384.0f / 65535.0f, 1e-6f);
  EXPECT_EQ(second[2].color, glm::vec4(1, 1, 1, 0));
  EXPECT_EQ(second[1].uv1, second[1].uv);  // no TEXCOORD_1: set 0 stands in
  const auto& third = scene.meshes[2].primitives[0].vertices;
  EXPECT_EQ(third[0].color, glm::vec4(0.25f, 0.5f, 0.75f, 1));
  EXPECT_EQ(third[1].color, glm::vec4(1, 0, 0, 0));  // 2 and -1 clamped, with a warning
  EXPECT_TRUE(any_warning(scene, "meshes[2].primitives[0].attributes.COLOR_0"));
  EXPECT_EQ(scene.meshes[0].primitives[0].vertices.size(), 3u);

  const Material& m = scene.materials[0];
  EXPECT_EQ(m.mappings[0].tex_coord, 1);  // the extension's texCoord overrides the slot's 0
  EXPECT_EQ(m.mappings[0].offset, glm::vec2(0.5f, -0.25f));
  EXPECT_EQ(m.mappings[0].scale, glm::vec2(2, 4));
  EXPECT_EQ(m.mappings[3].tex_coord, 1);
  EXPECT_EQ(m.mappings[4].tex_coord, 0);  // TEXCOORD_3: not supported, set 0 with a warning
  EXPECT_TRUE(any_warning(scene, "materials[0].emissiveTexture.texCoord: TEXCOORD_3"));
  // KHR_texture_transform: (u, v) scaled to (2u, 4v), rotated by +90° with the extension's
  // matrix ((cos, sin), (-sin, cos)) to (4v, -2u), then offset.
  const glm::vec2 mapped = m.mappings[0].apply(glm::vec2(0.25f, 0.5f));
  EXPECT_NEAR(mapped.x, 4 * 0.5f + 0.5f, 1e-6f);
  EXPECT_NEAR(mapped.y, -2 * 0.25f - 0.25f, 1e-6f);

  // A transform that is not numbers is refused at its field.
  w.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]
       ["KHR_texture_transform"]["scale"] = {1, "x"};
  std::ofstream(dir_ / "colours.gltf") << w.doc.dump();
  EXPECT_TRUE(contains(load_error(dir_ / "colours.gltf"),
                       "materials[0].pbrMetallicRoughness.baseColorTexture.extensions."
                       "KHR_texture_transform.scale[1]: expected a finite number"))
      << load_error(dir_ / "colours.gltf");
}

TEST_F(GltfLoader, SixteenBitTexture) {
  const std::vector<uint8_t> png = test::sixteen_bit_grey_png();
  std::ofstream(dir_ / "deep.png", std::ios::binary)
      .write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
  GltfWriter w;
  json p = w.triangle();
  p["material"] = 0;
  w.add_mesh_node(p);
  w.doc["images"] = {{{"uri", "deep.png"}}};
  w.doc["textures"] = {{{"source", 0}}};
  w.doc["materials"] = {{{"pbrMetallicRoughness", {{"metallicRoughnessTexture", {{"index", 0}}}}}}};
  w.write_gltf(dir_ / "deep.gltf");
  const Scene scene = load_gltf(dir_ / "deep.gltf");
  ASSERT_EQ(scene.textures.size(), 1u) << (scene.warnings.empty() ? "" : scene.warnings[0]);
  const Texture& t = scene.textures[0];
  EXPECT_EQ(t.bits, 16u);
  EXPECT_FALSE(t.srgb);
  ASSERT_EQ(t.pixels.size(), 2u * 4u * 2u);
  uint16_t texel[8];
  std::memcpy(texel, t.pixels.data(), sizeof(texel));
  EXPECT_EQ(texel[0], 0x1234);
  EXPECT_EQ(texel[2], 0x1234);
  EXPECT_EQ(texel[3], 0xffff);  // opaque
  EXPECT_EQ(texel[4], 0xffff);
}

TEST_F(GltfLoader, NegativeScaleMirrorsTheInstance) {
  GltfWriter w;
  w.add_mesh_node(w.triangle(), {{"scale", {-1, 1, 1}}});
  w.write_glb(dir_ / "mirror.glb");
  const Scene scene = load_gltf(dir_ / "mirror.glb");
  const auto instances = scene.instances();
  ASSERT_EQ(instances.size(), 1u);
  EXPECT_TRUE(instances[0].mirrored);
}

TEST_F(GltfLoader, AnimationsAreLoaded) {
  GltfWriter w;
  const int node = w.add_mesh_node(w.triangle());
  const int input = w.add_floats({0, 1}, "SCALAR", 1);
  const int output = w.add_floats({0, 0, 0, 4, 0, 0}, "VEC3", 3);
  json channel = {{"sampler", 0}, {"target", {{"node", node}, {"path", "translation"}}}};
  json sampler = {{"input", input}, {"output", output}};
  json animation = {{"channels", json::array({channel})}, {"samplers", json::array({sampler})}};
  w.doc["animations"] = json::array({animation});
  w.write_gltf(dir_ / "anim.gltf");
  Scene scene = load_gltf(dir_ / "anim.gltf");
  ASSERT_EQ(scene.animations.size(), 1u);
  EXPECT_EQ(scene.animations[0].duration, 1.0f);
  EXPECT_TRUE(scene.nodes[size_t(node)].animated);
  EXPECT_TRUE(scene.animate(0.5));
  EXPECT_EQ(scene.nodes[size_t(node)].translation, glm::vec3(2, 0, 0));
  EXPECT_TRUE(scene.features().has_dynamic_geometry);
}

TEST_F(GltfLoader, MissingFile) {
  const std::string message = load_error(dir_ / "nope.gltf");
  EXPECT_TRUE(contains(message, (dir_ / "nope.gltf").string())) << message;
  EXPECT_TRUE(contains(message, "does not exist")) << message;
}

TEST_F(GltfLoader, NotGltf) {
  std::ofstream(dir_ / "bad.gltf") << "{ \"asset\": { \"version\": \"2.0\" }, \"nodes\": [ {";
  const std::string message = load_error(dir_ / "bad.gltf");
  EXPECT_TRUE(contains(message, (dir_ / "bad.gltf").string())) << message;
  std::ofstream(dir_ / "text.gltf") << "hello";
  EXPECT_FALSE(load_error(dir_ / "text.gltf").empty());
  std::ofstream(dir_ / "empty.glb");
  EXPECT_FALSE(load_error(dir_ / "empty.glb").empty());
}

TEST_F(GltfLoader, TruncatedGlb) {
  GltfWriter w;
  w.add_mesh_node(w.triangle());
  std::vector<uint8_t> bytes = w.glb_bytes();
  for (size_t keep : {bytes.size() - 9, bytes.size() / 2, size_t(20), size_t(12), size_t(5)}) {
    const auto path = dir_ / ("cut" + std::to_string(keep) + ".glb");
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(keep));
    const std::string message = load_error(path);
    EXPECT_TRUE(contains(message, path.string())) << keep << ": " << message;
  }
}

TEST_F(GltfLoader, OutOfRangeAccessor) {
  GltfWriter w;
  json p = w.triangle();
  p["attributes"]["POSITION"] = 7;
  w.add_mesh_node(p);
  w.write_gltf(dir_ / "range.gltf");
  const std::string message = load_error(dir_ / "range.gltf");
  EXPECT_TRUE(contains(
      message, (dir_ / "range.gltf").string() + ": meshes[0].primitives[0].attributes.POSITION"))
      << message;
  EXPECT_TRUE(contains(message, "accessor 7 out of range")) << message;
}

TEST_F(GltfLoader, OutOfRangeIndexAndBufferView) {
  GltfWriter w;
  json p = w.triangle();
  p["indices"] = w.add_indices({0, 1, 3});
  w.add_mesh_node(p);
  w.write_gltf(dir_ / "index.gltf");
  std::string message = load_error(dir_ / "index.gltf");
  EXPECT_TRUE(contains(message, "meshes[0].primitives[0].indices")) << message;
  EXPECT_TRUE(contains(message, "index 3")) << message;

  GltfWriter v;
  json q = v.triangle();
  v.add_mesh_node(q);
  v.doc["accessors"][0]["count"] = 1000;  // more elements than the view holds
  v.write_gltf(dir_ / "view.gltf");
  message = load_error(dir_ / "view.gltf");
  EXPECT_TRUE(contains(message, "attributes.POSITION")) << message;

  GltfWriter m;
  json r = m.triangle();
  r["material"] = 3;
  m.add_mesh_node(r);
  m.write_gltf(dir_ / "material.gltf");
  message = load_error(dir_ / "material.gltf");
  EXPECT_TRUE(contains(message, "meshes[0].primitives[0].material")) << message;
}

// Counts and URIs that would make the loader allocate or read absurd amounts are refused with
// the field named, before anything of their size is allocated.
TEST_F(GltfLoader, HugeCountsAndFolderUrisAreRefused) {
  GltfWriter w;
  json p = w.triangle();
  w.add_mesh_node(p);
  w.doc["accessors"][0]["count"] = 2147483647;
  w.write_gltf(dir_ / "count.gltf");
  std::string message = load_error(dir_ / "count.gltf");
  EXPECT_TRUE(contains(message, "attributes.POSITION (accessors[0]): 2147483647 elements"))
      << message;

  GltfWriter z;
  json q = z.triangle();
  z.add_mesh_node(q);
  z.doc["accessors"][0].erase("bufferView");  // reads as zeros: nothing bounds the count
  z.doc["accessors"][0]["count"] = 2147483647;
  z.write_gltf(dir_ / "zeros.gltf");
  message = load_error(dir_ / "zeros.gltf");
  EXPECT_TRUE(contains(message, "count 2147483647 without a bufferView")) << message;

  GltfWriter f;
  json r = f.triangle();
  f.add_mesh_node(r);
  f.write_gltf(dir_ / "folder.gltf");
  std::filesystem::create_directories(dir_ / "a_folder");
  f.doc["buffers"][0]["uri"] = "a_folder";
  std::ofstream(dir_ / "folder.gltf") << f.doc.dump(2);
  message = load_error(dir_ / "folder.gltf");
  EXPECT_TRUE(contains(message, (dir_ / "folder.gltf").string())) << message;
  EXPECT_TRUE(contains(message, "is a folder, expected a file")) << message;
}

// tinygltf indexes a GLB's buffer data unchecked when the buffer declares byteLength 0 while
// views use it: it threw std::out_of_range, and the message named no file.
TEST_F(GltfLoader, GlbBufferOfLengthZeroIsRefusedWithTheFile) {
  GltfWriter w;
  w.add_mesh_node(w.triangle());
  std::vector<uint8_t> glb = w.glb_bytes();
  std::string bytes(glb.begin(), glb.end());
  const std::string declared =
      "\"buffers\":[{\"byteLength\":" + std::to_string(w.bin.size()) + "}]";
  std::string zero = "\"buffers\":[{\"byteLength\":0}]";
  zero.resize(declared.size(), ' ');  // same length: the chunk sizes stay right
  const size_t at = bytes.find(declared);
  ASSERT_NE(at, std::string::npos);
  bytes.replace(at, declared.size(), zero);
  std::ofstream(dir_ / "zero.glb", std::ios::binary) << bytes;
  const std::string message = load_error(dir_ / "zero.glb");
  EXPECT_TRUE(contains(message, (dir_ / "zero.glb").string() + ": glb: not a valid glTF 2.0 file"))
      << message;
}

// Documents the glTF 2.0 specification allows that the parser refused: each loads, with a
// warning where the meaning changes.
TEST_F(GltfLoader, SpecificationAllowedDocumentsTheParserRefusedLoad) {
  {  // integers written as floats
    GltfWriter w;
    w.add_mesh_node(w.triangle());
    w.doc["accessors"][0]["count"] = 3.0;
    w.doc["accessors"][0]["componentType"] = 5126.0;
    w.doc["scene"] = 0.0;
    w.write_gltf(dir_ / "floats.gltf");
    EXPECT_EQ(load_error(dir_ / "floats.gltf"), "");
  }
  {  // a skin without inverseBindMatrices (identity)
    GltfWriter w;
    const int joint = w.add_node({{"name", "joint"}});
    w.add_mesh_node(w.triangle(), {{"skin", 0}});
    w.doc["skins"] = {{{"joints", {joint}}}};
    w.write_gltf(dir_ / "skin.gltf");
    const Scene scene = load_gltf(dir_ / "skin.gltf");
    EXPECT_TRUE(any_warning(scene, "skins[0]: no inverseBindMatrices"));
  }
  {  // an unused buffer without a uri in a .gltf
    GltfWriter w;
    w.add_mesh_node(w.triangle());
    w.write_gltf(dir_ / "buffer.gltf");
    w.doc["buffers"].push_back({{"byteLength", 16}});
    std::ofstream(dir_ / "buffer.gltf") << w.doc.dump();
    const Scene scene = load_gltf(dir_ / "buffer.gltf");
    EXPECT_TRUE(any_warning(scene, "buffers[1]: no uri"));
  }
  {  // an animation channel whose target names no node (KHR_animation_pointer)
    GltfWriter w;
    const int node = w.add_mesh_node(w.triangle());
    const int times = w.add_floats({0, 1}, "SCALAR", 1);
    const int values = w.add_floats({0, 0, 0, 1, 0, 0}, "VEC3", 3);
    w.doc["animations"] = {
        {{"samplers", {{{"input", times}, {"output", values}}}},
         {"channels",
          {{{"sampler", 0}, {"target", {{"path", "pointer"}}}},
           {{"sampler", 0}, {"target", {{"node", node}, {"path", "translation"}}}}}}}};
    w.write_gltf(dir_ / "pointer.gltf");
    const Scene scene = load_gltf(dir_ / "pointer.gltf");
    EXPECT_TRUE(any_warning(scene, "animations[0].channels[0]: the target names no node"));
    ASSERT_EQ(scene.animations.size(), 1u);
    EXPECT_EQ(scene.animations[0].channels.size(), 1u);
  }
}

TEST_F(GltfLoader, MissingBufferFileNamesTheFieldAndTheFolder) {
  GltfWriter w;
  w.add_mesh_node(w.triangle());
  w.write_gltf(dir_ / "moved.gltf");
  std::filesystem::remove(dir_ / "moved.bin");
  const std::string message = load_error(dir_ / "moved.gltf");
  EXPECT_TRUE(contains(message, (dir_ / "moved.gltf").string() +
                                    ": buffers[0].uri: file 'moved.bin' not found in " +
                                    dir_.string()))
      << message;
}

// A light index far outside int's range is refused before any conversion (a fuzzer found the
// overflow).
TEST_F(GltfLoader, HugeLightIndexIsRefused) {
  std::ofstream(dir_ / "light.gltf") << R"({"asset":{"version":"2.0"},"scene":0,
    "scenes":[{"nodes":[0]}],"extensionsUsed":["KHR_lights_punctual"],
    "nodes":[{"extensions":{"KHR_lights_punctual":{"light":1e19}}}],
    "extensions":{"KHR_lights_punctual":{"lights":[{"type":"point"}]}}})";
  const std::string message = load_error(dir_ / "light.gltf");
  EXPECT_TRUE(contains(message,
                       "nodes[0].extensions.KHR_lights_punctual.light: expected a light "
                       "index from 0 to 0"))
      << message;
}

// EXT_mesh_gpu_instancing: instances whose transform is not finite are skipped, with one
// warning for the node rather than one per instance; a zero rotation reads as the identity.
TEST_F(GltfLoader, InstancesWithNonFiniteTransformsAreSkippedWithOneWarning) {
  GltfWriter w;
  w.add_mesh_node(w.triangle());
  const float nan = std::nanf("");
  const int translations = w.add_floats({0, 0, 0, nan, 0, 0, 1, 1, 1, 0, nan, 0}, "VEC3", 3);
  w.doc["accessors"].push_back({{"componentType", 5126}, {"type", "VEC4"}, {"count", 4}});
  const int zero_rotations = int(w.doc["accessors"].size()) - 1;
  w.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = {
      {"TRANSLATION", translations}, {"ROTATION", zero_rotations}};
  w.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
  w.write_gltf(dir_ / "instances.gltf");
  const Scene scene = load_gltf(dir_ / "instances.gltf");
  EXPECT_EQ(scene.instances().size(), 2u);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_TRUE(any_warning(scene, "2 of 4 instances have a non-finite transform"));
}

TEST_F(GltfLoader, NodeCycleIsAnError) {
  GltfWriter w;
  w.add_node({{"children", {1}}});
  w.add_node({{"children", {0}}}, false);
  w.write_gltf(dir_ / "cycle.gltf");
  const std::string message = load_error(dir_ / "cycle.gltf");
  EXPECT_TRUE(contains(message, "nodes[")) << message;
}

}  // namespace
}  // namespace voxgi::scene
