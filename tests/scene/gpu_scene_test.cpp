#include <gtest/gtest.h>

#include <cstring>

#include "engine/gpu/context.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/gpu/shader_compiler.hpp"
#include "engine/scene/builtin_scenes.hpp"
#include "engine/scene/bvh.hpp"
#include "engine/scene/gpu_bvh.hpp"
#include "engine/scene/gpu_scene.hpp"
#include "engine/scene/scene_builder.hpp"
#include "tests/gpu/gpu_test_env.hpp"
#include "tests/gpu/shader_files.hpp"

namespace voxgi::scene {
namespace {

class GpuSceneTest : public test::GpuTest {};

template <typename T>
std::vector<T> read_back(const gpu::Buffer& buffer, size_t count, VkDeviceSize offset = 0) {
  return const_cast<gpu::Buffer&>(buffer).download_vector<T>(count, offset);
}

TEST_F(GpuSceneTest, CornellBuffersMatchTheCpuScene) {
  const Scene scene = make_builtin_scene("cornell");
  GpuScene gpu(context(), scene);
  EXPECT_NE(gpu.set_layout(), VK_NULL_HANDLE);
  EXPECT_NE(gpu.descriptor_set(), VK_NULL_HANDLE);
  EXPECT_EQ(gpu.light_count(), 1u);
  EXPECT_EQ(gpu.texture_count(), 0u);

  // Vertices and indices: the primitives concatenated in mesh order.
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;
  for (const Mesh& mesh : scene.meshes) {
    for (const Primitive& p : mesh.primitives) {
      vertices.insert(vertices.end(), p.vertices.begin(), p.vertices.end());
      indices.insert(indices.end(), p.indices.begin(), p.indices.end());
    }
  }
  const auto gpu_vertices = read_back<Vertex>(gpu.vertices(), vertices.size());
  ASSERT_EQ(gpu_vertices.size(), vertices.size());
  EXPECT_EQ(std::memcmp(gpu_vertices.data(), vertices.data(), vertices.size() * sizeof(Vertex)), 0);
  EXPECT_EQ(read_back<uint32_t>(gpu.indices(), indices.size()), indices);

  // Draws cover every triangle once, each with its instance and material.
  const auto instances = scene.instances();
  ASSERT_EQ(gpu.draws().size(), instances.size());
  uint32_t drawn = 0;
  for (const GpuScene::Draw& draw : gpu.draws()) {
    const Instance& instance = instances[draw.instance];
    const Primitive& p = scene.meshes[size_t(instance.mesh)].primitives[size_t(instance.primitive)];
    EXPECT_EQ(draw.index_count, p.indices.size());
    EXPECT_EQ(int(draw.material), p.material);
    EXPECT_EQ(indices[draw.first_index], p.indices[0]);
    EXPECT_EQ(vertices[size_t(draw.vertex_offset)].position, p.vertices[0].position);
    EXPECT_FALSE(draw.blend);
    drawn += draw.index_count / 3;
  }
  EXPECT_EQ(drawn, scene.features().triangle_count);

  // Materials (plus the default one at the end), instances and lights.
  const auto materials = read_back<GpuMaterial>(gpu.materials(), scene.materials.size() + 1);
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    EXPECT_EQ(materials[i].base_color, scene.materials[i].base_color);
    EXPECT_EQ(materials[i].emissive, scene.materials[i].emissive);
    EXPECT_EQ(materials[i].roughness, scene.materials[i].roughness);
    EXPECT_EQ(materials[i].base_color_tex, -1);
  }
  const auto gpu_instances = read_back<GpuInstance>(gpu.instances(), instances.size());
  for (size_t i = 0; i < instances.size(); ++i) {
    EXPECT_EQ(gpu_instances[i].world, instances[i].world);
    EXPECT_EQ(gpu_instances[i].flags, 0u);
  }
  const auto header = read_back<GpuLightHeader>(gpu.lights(), 1);
  EXPECT_EQ(header[0].count, 1u);
  const auto lights = read_back<GpuLight>(gpu.lights(), 1, sizeof(GpuLightHeader));
  EXPECT_EQ(lights[0].type, uint32_t(GpuLightType::Point));
  EXPECT_EQ(lights[0].position, scene.lights[0].position);
  EXPECT_EQ(lights[0].radiance, scene.lights[0].color * scene.lights[0].intensity);
  EXPECT_EQ(lights[0].spot_scale, 0.0f);
  EXPECT_EQ(lights[0].spot_offset, 1.0f);
  EXPECT_EQ(lights[0].shadow_index, 0);
}

TEST_F(GpuSceneTest, EmptySceneWorks) {
  const Scene scene = make_builtin_scene("empty");
  GpuScene gpu(context(), scene);
  EXPECT_EQ(gpu.srgb_textures().desc().array_layers, 1u);  // a white layer
  EXPECT_EQ(gpu.linear_textures().extent().width, 1u);
  EXPECT_TRUE(gpu.draws().empty());
  EXPECT_EQ(gpu.light_count(), 0u);
  EXPECT_NE(gpu.descriptor_set(), VK_NULL_HANDLE);
  EXPECT_EQ(read_back<GpuLightHeader>(gpu.lights(), 1)[0].count, 0u);
  EXPECT_FALSE(gpu.update(scene));
}

TEST_F(GpuSceneTest, SpotLightConeAndTextures) {
  SceneBuilder b("textured");
  Texture colour;
  colour.name = "checker";
  colour.width = 3;
  colour.height = 5;  // not a power of two
  colour.srgb = true;
  colour.pixels.assign(3 * 5 * 4, 200);
  Texture deep;
  deep.name = "deep";
  deep.width = 4;
  deep.height = 4;
  deep.bits = 16;
  deep.wrap_repeat = false;
  deep.pixels.assign(4 * 4 * 4 * 2, 0x80);
  Material m;
  m.base_color_tex = b.add_texture(colour);
  m.metallic_roughness_tex = b.add_texture(deep);
  m.alpha_mode = AlphaMode::Blend;
  m.double_sided = true;
  b.add_quad("q", {0, 0, 0}, {1, 0, 0}, {0, 0, -1}, b.add_material(m));
  Light spot;
  spot.type = LightType::Spot;
  spot.inner_cone = 0.3f;
  spot.outer_cone = 0.6f;
  b.add_light(spot, {0, 1, 0}, {0, -1, 0});
  const Scene scene = b.finish();
  GpuScene gpu(context(), scene);
  EXPECT_EQ(gpu.texture_count(), 2u);
  // One layer in each array, each array as large as its largest texture.
  EXPECT_EQ(gpu.srgb_textures().format(), VK_FORMAT_R8G8B8A8_SRGB);
  EXPECT_EQ(gpu.srgb_textures().desc().array_layers, 1u);
  EXPECT_EQ(gpu.srgb_textures().extent().width, 3u);
  EXPECT_EQ(gpu.srgb_textures().extent().height, 5u);
  EXPECT_EQ(gpu.linear_textures().format(), VK_FORMAT_R16G16B16A16_UNORM);
  const GpuMaterial& material = gpu.gpu_materials()[0];
  EXPECT_EQ(material.base_color_tex, 0);
  EXPECT_EQ(material.metallic_roughness_tex, 0);
  EXPECT_EQ(material.normal_tex, -1);
  EXPECT_EQ(material.clamp_mask, 2u);  // the 16-bit texture clamps
  // Pixels arrive unchanged when no resampling is needed.
  auto& srgb = const_cast<gpu::Image&>(gpu.srgb_textures());
  const auto texels = srgb.download(VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  EXPECT_EQ(texels, colour.pixels);
  ASSERT_EQ(gpu.draws().size(), 1u);
  EXPECT_TRUE(gpu.draws()[0].blend);
  EXPECT_TRUE(gpu.draws()[0].double_sided);
  const GpuLight light = gpu.gpu_lights()[0];
  EXPECT_EQ(light.type, uint32_t(GpuLightType::Spot));
  // Full intensity at the inner cone, zero at the outer one.
  EXPECT_NEAR(std::cos(0.3f) * light.spot_scale + light.spot_offset, 1.0f, 1e-5f);
  EXPECT_NEAR(std::cos(0.6f) * light.spot_scale + light.spot_offset, 0.0f, 1e-5f);
  EXPECT_NEAR(light.direction.y, -1.0f, 1e-6f);
}

TEST_F(GpuSceneTest, TexturesResampleToTheLayerSizeAndSplitByUse) {
  SceneBuilder b("layers");
  Texture small;
  small.name = "small";
  small.width = 2;
  small.height = 2;
  small.pixels.assign(2 * 2 * 4, 0);
  for (size_t i = 0; i < small.pixels.size(); i += 4) small.pixels[i] = 255;  // red
  Texture big = small;
  big.name = "big";
  big.width = 8;
  big.height = 4;
  big.pixels.assign(8 * 4 * 4, 77);
  Material m;
  m.base_color_tex = b.add_texture(small);
  m.emissive_tex = b.add_texture(big);
  m.occlusion_tex = m.base_color_tex;  // the same texture used linearly
  b.add_quad("q", {0, 0, 0}, {1, 0, 0}, {0, 0, -1}, b.add_material(m));
  const Scene scene = b.finish();
  GpuScene gpu(context(), scene);
  const GpuMaterial& g = gpu.gpu_materials()[0];
  EXPECT_EQ(g.base_color_tex, 0);
  EXPECT_EQ(g.emissive_tex, 1);
  EXPECT_EQ(g.occlusion_tex, 0);
  EXPECT_EQ(gpu.srgb_textures().desc().array_layers, 2u);
  EXPECT_EQ(gpu.srgb_textures().extent().width, 8u);
  EXPECT_EQ(gpu.srgb_textures().extent().height, 4u);
  EXPECT_EQ(gpu.linear_textures().extent().width, 2u);
  auto& srgb = const_cast<gpu::Image&>(gpu.srgb_textures());
  const auto layer0 = srgb.download(VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 0, 0);
  ASSERT_EQ(layer0.size(), 8u * 4u * 4u);
  for (size_t i = 0; i < layer0.size(); i += 4) {
    EXPECT_EQ(layer0[i], 255);
    EXPECT_EQ(layer0[i + 1], 0);
  }
  const auto layer1 = srgb.download(VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 0, 1);
  EXPECT_EQ(layer1, big.pixels);
}

TEST_F(GpuSceneTest, UpdateUploadsMovedInstancesAndMirrorsWinding) {
  SceneBuilder b("moving");
  const int material = b.add_material(Material{});
  const int node = b.add_quad("q", {0, 0, 0}, {1, 0, 0}, {0, 0, -1}, material);
  Light point;
  b.add_light(point, {0, 1, 0});
  Animation animation;
  AnimationChannel channel;
  channel.node = node;
  channel.path = AnimationPath::Scale;
  channel.interpolation = Interpolation::Step;
  channel.times = {0.0f, 1.0f};
  channel.values = {glm::vec4(1, 1, 1, 0), glm::vec4(-1, 1, 1, 0)};
  animation.channels.push_back(channel);
  animation.duration = 2.0f;
  b.scene().animations.push_back(animation);
  b.scene().nodes[size_t(node)].animated = true;
  Scene scene = b.finish();

  GpuScene gpu(context(), scene);
  EXPECT_FALSE(gpu.update(scene));
  const uint32_t first = gpu.draws()[0].first_index;
  EXPECT_TRUE(scene.animate(1.5));
  EXPECT_TRUE(gpu.update(scene));
  const auto instances = read_back<GpuInstance>(gpu.instances(), 1);
  EXPECT_EQ(instances[0].world[0][0], -1.0f);
  EXPECT_EQ(instances[0].flags, kInstanceMirrored);
  // The mirrored draw uses the winding-swapped copy of the indices.
  const GpuScene::Draw& draw = gpu.draws()[0];
  EXPECT_NE(draw.first_index, first);
  const auto original = read_back<uint32_t>(gpu.indices(), 3, first * sizeof(uint32_t));
  const auto flipped = read_back<uint32_t>(gpu.indices(), 3, draw.first_index * sizeof(uint32_t));
  EXPECT_EQ(flipped, (std::vector<uint32_t>{original[0], original[2], original[1]}));
}

// Reads set 1 through shaders/lib/scene.glsl, so the GLSL structs must match the C++ ones.
const char* kReadSceneShader = R"(#version 460
#extension GL_GOOGLE_include_directive : require
#define SCENE_TEXTURE_EXPLICIT_LOD
#include "lib/scene.glsl"
layout(local_size_x = 1) in;
layout(set = 0, binding = 0, std430) writeonly buffer Out { float values[]; };
void main() {
  SceneMaterial m = scene_materials[1];
  values[0] = m.roughness;
  values[1] = m.emissive.z;
  values[2] = float(m.base_color_tex);
  values[3] = float(m.alpha_mode);
  SceneInstance instance = scene_instances[0];
  values[4] = instance.world[3].x;
  values[5] = float(instance.material);
  values[6] = instance.normal_matrix[1][1];
  values[7] = float(scene_light_count());
  SceneLight light = scene_lights[0];
  values[8] = light.radiance.y;
  values[9] = light.spot_offset;
  values[10] = float(light.type);
  values[11] = light.direction.y;
  values[12] = light.position.y;
  values[13] = float(light.shadow_index);
  SurfaceAttributes left = SurfaceAttributes(vec2(0.25, 0.5), vec2(0.0), vec4(1.0));
  MaterialSample s = sample_material(1u, left, vec3(0.0, 0.0, 2.0), vec4(1.0, 0.0, 0.0, 1.0));
  values[14] = s.base_color.r;
  values[15] = s.normal.z;
  values[16] = s.roughness;
  values[17] = s.alpha_blend ? 1.0 : 0.0;
  vec4 t = scene_world_tangent(instance, vec4(1.0, 0.0, 0.0, 1.0));
  values[18] = t.w;
  // Material 2 reads TEXCOORD_1 through u' = 0.5 u + 0.5 (the white half) and the vertex
  // colour multiplies.
  SurfaceAttributes mapped = SurfaceAttributes(vec2(0.25, 0.5), vec2(0.5), vec4(0.5, 1.0, 1.0, 0.25));
  vec4 c = sample_material(2u, mapped, vec3(0.0, 0.0, 1.0), vec4(1.0, 0.0, 0.0, 1.0)).base_color;
  values[19] = c.r;
  values[20] = c.a;
}
)";

// The BVH service: built once on first use, the same object for every caller, refit when an
// instance moved, with the nodes a CPU refit of the same tree gives.
TEST_F(GpuSceneTest, BvhIsBuiltOnceAndRefitWhenInstancesMove) {
  Scene scene = make_builtin_scene("cornell");
  GpuScene gpu(context(), scene);
  EXPECT_FALSE(gpu.has_bvh());
  const GpuBvh& first = gpu.bvh(scene);
  EXPECT_TRUE(gpu.has_bvh());
  EXPECT_EQ(&gpu.bvh(scene), &first);
  Bvh expected = Bvh::build(scene);
  ASSERT_EQ(first.node_count(), expected.nodes().size());
  const std::vector<GpuBvhNode> built = read_back<GpuBvhNode>(first.nodes(), first.node_count());

  int block = -1;
  for (size_t i = 0; i < scene.nodes.size(); ++i) {
    if (scene.nodes[i].name == "tall_block") block = static_cast<int>(i);
  }
  ASSERT_GE(block, 0);
  scene.nodes[size_t(block)].translation += glm::vec3(-0.12f, 0.0f, -0.1f);
  scene.update_transforms();
  const GpuBvh& refit = gpu.bvh(scene);
  EXPECT_EQ(&refit, &first);
  expected.refit(scene);
  const std::vector<GpuBvhNode> nodes = read_back<GpuBvhNode>(refit.nodes(), refit.node_count());
  ASSERT_EQ(nodes.size(), expected.nodes().size());
  EXPECT_NE(std::memcmp(nodes.data(), built.data(), nodes.size() * sizeof(GpuBvhNode)), 0);
  for (size_t i = 0; i < nodes.size(); ++i) {
    EXPECT_EQ(nodes[i].bounds_min, expected.nodes()[i].bounds_min) << i;
    EXPECT_EQ(nodes[i].bounds_max, expected.nodes()[i].bounds_max) << i;
  }
}

TEST_F(GpuSceneTest, ShadersSeeTheSameData) {
  SceneBuilder b("shader");
  b.add_material(Material{});
  Texture colour;
  colour.name = "grey-white";
  // Left half sRGB 188 ≈ linear 0.5, right half white; wide, so that the samples below lie
  // texels away from the edge (lavapipe's anisotropic filter takes taps around the point even
  // at an explicit lod: 9% of the neighbour at a texel's centre).
  colour.width = 64;
  colour.height = 1;
  colour.srgb = true;
  for (uint32_t x = 0; x < colour.width; ++x) {
    const uint8_t value = x < colour.width / 2 ? 188 : 255;
    colour.pixels.insert(colour.pixels.end(), {value, value, value, 255});
  }
  Material m;
  m.base_color = glm::vec4(0.5f, 1.0f, 1.0f, 1.0f);
  m.roughness = 0.01f;  // clamped to 0.03 by sample_material
  m.emissive = glm::vec3(0, 0, 7);
  m.alpha_mode = AlphaMode::Blend;
  m.base_color_tex = b.add_texture(colour);
  const int material = b.add_material(m);
  Material mapped = m;
  mapped.alpha_mode = AlphaMode::Mask;
  mapped.mappings[0].tex_coord = 1;
  mapped.mappings[0].offset = glm::vec2(0.5f, 0.0f);
  mapped.mappings[0].scale = glm::vec2(0.5f, 1.0f);
  b.add_material(mapped);
  const int node = b.add_quad("q", {0, 0, 0}, {1, 0, 0}, {0, 0, -1}, material);
  b.scene().nodes[size_t(node)].translation = glm::vec3(3, 0, 0);
  b.scene().nodes[size_t(node)].scale = glm::vec3(-1, 2, 1);
  Light spot;
  spot.type = LightType::Spot;
  spot.color = glm::vec3(1, 0.5f, 0.25f);
  spot.intensity = 8.0f;
  b.add_light(spot, {0, 4, 0}, {0, -1, 0});
  const Scene scene = b.finish();
  GpuScene gpu(context(), scene);

  const auto dir = test::make_temp_dir("voxgi-scene-shader");
  test::write_file(dir / "read_scene.comp", kReadSceneShader);
  gpu::ShaderCompiler compiler({dir, std::filesystem::path(VOXGI_SOURCE_DIR) / "shaders"}, "");
  const auto spirv = compiler.compile({"read_scene.comp"});
  gpu::PipelineLayoutDesc layout;
  layout.bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}};
  layout.extra_set_layouts = {gpu.set_layout()};
  gpu::ComputePipeline pipeline(context(), spirv, layout, "test.read_scene");
  gpu::Buffer out(context(), 32 * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                  gpu::MemoryUsage::GpuOnly, "test.read_scene.out");
  context().immediate_submit([&](VkCommandBuffer cmd) {
    pipeline.bind(cmd);
    gpu::DescriptorWriter().storage_buffer(0, out).push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE,
                                                        pipeline.layout());
    const VkDescriptorSet set = gpu.descriptor_set();
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout(), 1, 1, &set, 0,
                            nullptr);
    vkCmdDispatch(cmd, 1, 1, 1);
  });
  const auto v = out.download_vector<float>();
  EXPECT_FLOAT_EQ(v[0], 0.01f);
  EXPECT_FLOAT_EQ(v[1], 7.0f);
  EXPECT_EQ(v[2], 0.0f);
  EXPECT_EQ(v[3], 2.0f);
  EXPECT_EQ(v[4], 3.0f);
  EXPECT_EQ(v[5], 1.0f);
  EXPECT_FLOAT_EQ(v[6], 0.5f);  // inverse transpose of scale 2
  EXPECT_EQ(v[7], 1.0f);
  EXPECT_FLOAT_EQ(v[8], 4.0f);
  EXPECT_FLOAT_EQ(v[9], gpu.gpu_lights()[0].spot_offset);
  EXPECT_EQ(v[10], 2.0f);
  EXPECT_NEAR(v[11], -1.0f, 1e-6f);
  EXPECT_FLOAT_EQ(v[12], 4.0f);
  EXPECT_EQ(v[13], 0.0f);
  EXPECT_NEAR(v[14], 0.5f * 0.5029f, 0.01f);  // factor × decoded sRGB texel
  EXPECT_FLOAT_EQ(v[15], 1.0f);
  EXPECT_FLOAT_EQ(v[16], 0.03f);
  EXPECT_EQ(v[17], 1.0f);
  EXPECT_EQ(v[18], -1.0f);                        // mirrored instance flips the handedness
  EXPECT_NEAR(v[19], 0.5f * 1.0f * 0.5f, 1e-3f);  // factor × white texel × vertex colour
  EXPECT_FLOAT_EQ(v[20], 0.25f);                  // alpha: factor 1 × texel 1 × vertex 0.25
}

TEST(GpuSceneLayout, VertexInputMatchesVertex) {
  const auto attributes = GpuScene::vertex_attributes();
  ASSERT_EQ(attributes.size(), 6u);
  EXPECT_EQ(attributes[2].offset, offsetof(Vertex, tangent));
  EXPECT_EQ(attributes[3].offset, 40u);
  EXPECT_EQ(attributes[4].offset, 48u);
  EXPECT_EQ(attributes[5].offset, 56u);
  EXPECT_EQ(GpuScene::vertex_binding().stride, 72u);
}

}  // namespace
}  // namespace voxgi::scene
