#include "engine/scene/gpu_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "engine/gpu/context.hpp"
#include "engine/gpu/error.hpp"
#include "engine/scene/bvh.hpp"
#include "engine/scene/geometry.hpp"
#include "engine/scene/gpu_bvh.hpp"

namespace voxgi::scene {

namespace {

// Whether the node or one of its ancestors is animated (its world matrix may change).
bool may_move(const Scene& scene, int node) {
  for (int n = node; n >= 0; n = scene.nodes[size_t(n)].parent) {
    if (scene.nodes[size_t(n)].animated) return true;
  }
  return false;
}

template <typename T>
std::unique_ptr<gpu::Buffer> make_buffer(gpu::Context& context, const std::vector<T>& data,
                                         VkBufferUsageFlags usage, const char* name) {
  // At least one element, so empty scenes still bind valid buffers.
  const VkDeviceSize size = std::max<VkDeviceSize>(sizeof(T), data.size() * sizeof(T));
  auto buffer =
      std::make_unique<gpu::Buffer>(context, size, usage, gpu::MemoryUsage::GpuOnly, name);
  if (!data.empty()) {
    buffer->upload_vector(data);
  } else {
    const std::vector<uint8_t> zeros(size, 0);
    buffer->upload_vector(zeros);
  }
  return buffer;
}

}  // namespace

GpuLight to_gpu_light(const Light& light, int index) {
  GpuLight g{};
  g.position = light.position;
  g.direction = light.direction;
  g.range = light.range;
  g.radiance = light.color * light.intensity;
  g.shadow_index = index;
  switch (light.type) {
    case LightType::Directional:
      g.type = uint32_t(GpuLightType::Directional);
      break;
    case LightType::Point:
      g.type = uint32_t(GpuLightType::Point);
      break;
    case LightType::Spot:
      g.type = uint32_t(GpuLightType::Spot);
      break;
  }
  if (light.type == LightType::Spot) {
    const float cos_outer = std::cos(light.outer_cone);
    const float cos_inner = std::cos(light.inner_cone);
    g.spot_scale = 1.0f / std::max(0.001f, cos_inner - cos_outer);
    g.spot_offset = -cos_outer * g.spot_scale;
  } else {
    g.spot_scale = 0.0f;
    g.spot_offset = 1.0f;
  }
  return g;
}

GpuMaterial to_gpu_material(const Material& m) {
  GpuMaterial g{};
  g.base_color = m.base_color;
  g.emissive = m.emissive;
  g.metallic = m.metallic;
  g.roughness = m.roughness;
  g.normal_scale = m.normal_scale;
  g.occlusion_strength = m.occlusion_strength;
  g.alpha_cutoff = m.alpha_cutoff;
  g.base_color_tex = m.base_color_tex;
  g.metallic_roughness_tex = m.metallic_roughness_tex;
  g.normal_tex = m.normal_tex;
  g.occlusion_tex = m.occlusion_tex;
  g.emissive_tex = m.emissive_tex;
  g.alpha_mode = static_cast<uint32_t>(m.alpha_mode);
  g.double_sided = m.double_sided ? 1u : 0u;
  for (int slot = 0; slot < 5; ++slot) {
    glm::vec3 row0, row1;
    m.mappings[slot].matrix_rows(row0, row1);
    g.uv_rows[2 * slot] = glm::vec4(row0, float(m.mappings[slot].tex_coord));
    g.uv_rows[2 * slot + 1] = glm::vec4(row1, 0.0f);
  }
  return g;
}

GpuScene::GpuScene(gpu::Context& context, const Scene& scene) : context_(&context) {
  try {
    upload_geometry(scene);
    upload_textures(scene);
    upload_materials(scene);
    build_instances(scene, gpu_instances_);
    instances_ =
        make_buffer(context, gpu_instances_, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "scene.instances");
    build_lights(scene, gpu_lights_);
    lights_ = std::make_unique<gpu::Buffer>(
        context,
        sizeof(GpuLightHeader) + std::max<size_t>(1, gpu_lights_.size()) * sizeof(GpuLight),
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::GpuOnly, "scene.lights");
    upload_lights();
    create_descriptors();
  } catch (...) {
    release_descriptors();  // the members free themselves; the raw handles need this
    throw;
  }
}

// The BVH service behind GpuScene::bvh(): the tree, its GPU copy and the instance transforms
// it was last fitted to.
struct SceneBvh {
  Bvh bvh;
  std::unique_ptr<GpuBvh> gpu;
  std::vector<glm::mat4> worlds;
};

namespace {

std::vector<glm::mat4> instance_worlds(const Scene& scene) {
  std::vector<glm::mat4> worlds;
  for (const Instance& instance : scene.instances()) worlds.push_back(instance.world);
  return worlds;
}

}  // namespace

GpuScene::~GpuScene() {
  release_descriptors();
}

const GpuBvh& GpuScene::bvh(const Scene& scene) {
  std::vector<glm::mat4> worlds = instance_worlds(scene);
  if (!bvh_) {
    auto built = std::make_unique<SceneBvh>();
    built->bvh = Bvh::build(scene);
    built->gpu = std::make_unique<GpuBvh>(*context_, scene, built->bvh);
    built->worlds = std::move(worlds);
    bvh_ = std::move(built);
  } else if (worlds != bvh_->worlds) {
    bvh_->bvh.refit(scene);
    bvh_->gpu->update(scene, bvh_->bvh);
    bvh_->worlds = std::move(worlds);
  }
  return *bvh_->gpu;
}

void GpuScene::release_descriptors() {
  VkDevice device = context_->device();
  if (pool_) vkDestroyDescriptorPool(device, pool_, nullptr);
  if (set_layout_) vkDestroyDescriptorSetLayout(device, set_layout_, nullptr);
  if (srgb_view_) vkDestroyImageView(device, srgb_view_, nullptr);
  if (linear_view_) vkDestroyImageView(device, linear_view_, nullptr);
  srgb_view_ = linear_view_ = VK_NULL_HANDLE;
  pool_ = VK_NULL_HANDLE;
  set_layout_ = VK_NULL_HANDLE;
  set_ = VK_NULL_HANDLE;
}

void GpuScene::upload_geometry(const Scene& scene) {
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;
  ranges_.resize(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    ranges_[m].resize(scene.meshes[m].primitives.size());
    for (size_t p = 0; p < scene.meshes[m].primitives.size(); ++p) {
      const Primitive& primitive = scene.meshes[m].primitives[p];
      PrimitiveRange& range = ranges_[m][p];
      range.first_index = static_cast<uint32_t>(indices.size());
      range.index_count = static_cast<uint32_t>(primitive.indices.size());
      range.vertex_offset = static_cast<int32_t>(vertices.size());
      vertices.insert(vertices.end(), primitive.vertices.begin(), primitive.vertices.end());
      indices.insert(indices.end(), primitive.indices.begin(), primitive.indices.end());
    }
  }
  // Winding-swapped copies for primitives drawn mirrored now or possibly later (animated).
  cpu_instances_ = scene.instances();
  for (const Instance& instance : cpu_instances_) {
    PrimitiveRange& range = ranges_[size_t(instance.mesh)][size_t(instance.primitive)];
    if (range.flipped_first_index != UINT32_MAX) continue;
    if (!instance.mirrored && !may_move(scene, instance.node)) continue;
    const Primitive& primitive =
        scene.meshes[size_t(instance.mesh)].primitives[size_t(instance.primitive)];
    range.flipped_first_index = static_cast<uint32_t>(indices.size());
    const std::vector<uint32_t> flipped = flip_winding(primitive.indices);
    indices.insert(indices.end(), flipped.begin(), flipped.end());
  }
  vertices_ = make_buffer(*context_, vertices,
                          VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                          "scene.vertices");
  indices_ = make_buffer(*context_, indices,
                         VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                         "scene.indices");
}

void GpuScene::upload_materials(const Scene& scene) {
  std::vector<GpuMaterial> materials;
  for (const Material& m : scene.materials) {
    GpuMaterial g = to_gpu_material(m);
    // Scene texture indices become layers of the array the slot samples.
    int32_t* slots[5] = {&g.base_color_tex, &g.metallic_roughness_tex, &g.normal_tex,
                         &g.occlusion_tex, &g.emissive_tex};
    for (int slot = 0; slot < 5; ++slot) {
      const int32_t tex = *slots[slot];
      if (tex < 0 || tex >= static_cast<int32_t>(scene.textures.size())) {
        *slots[slot] = -1;
        continue;
      }
      const bool srgb_slot = slot == 0 || slot == 4;
      *slots[slot] = srgb_slot ? srgb_layer_[size_t(tex)] : linear_layer_[size_t(tex)];
      if (!scene.textures[size_t(tex)].wrap_repeat) g.clamp_mask |= 1u << slot;
    }
    materials.push_back(g);
  }
  // glTF's default material, for primitives without one.
  Material fallback;
  fallback.name = "default";
  default_material_ = static_cast<uint32_t>(materials.size());
  materials.push_back(to_gpu_material(fallback));
  materials_ =
      make_buffer(*context_, materials, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "scene.materials");
  gpu_materials_ = std::move(materials);
}

namespace {

// One texel of t as RGBA in [0, 1].
glm::vec4 texel(const Texture& t, uint32_t x, uint32_t y) {
  const size_t i = (size_t(y) * t.width + x) * 4;
  glm::vec4 v;
  for (int c = 0; c < 4; ++c) {
    if (t.bits == 16) {
      uint16_t raw;
      std::memcpy(&raw, t.pixels.data() + (i + size_t(c)) * 2, 2);
      v[c] = float(raw) / 65535.0f;
    } else {
      v[c] = float(t.pixels[i + size_t(c)]) / 255.0f;
    }
  }
  return v;
}

// Bilinear resample of t to width × height, written as `bits`-bit RGBA to out. Texture values
// are stored as they come (sRGB-encoded for sRGB textures); only the resolution changes.
void resample(const Texture& t, uint32_t width, uint32_t height, uint32_t bits, uint8_t* out) {
  const bool same = t.width == width && t.height == height;
  for (uint32_t y = 0; y < height; ++y) {
    for (uint32_t x = 0; x < width; ++x) {
      glm::vec4 v;
      if (same) {
        v = texel(t, x, y);
      } else {
        const float sx = std::clamp((float(x) + 0.5f) * float(t.width) / float(width) - 0.5f, 0.0f,
                                    float(t.width - 1));
        const float sy = std::clamp((float(y) + 0.5f) * float(t.height) / float(height) - 0.5f,
                                    0.0f, float(t.height - 1));
        const uint32_t x0 = uint32_t(sx), y0 = uint32_t(sy);
        const uint32_t x1 = std::min(x0 + 1, t.width - 1), y1 = std::min(y0 + 1, t.height - 1);
        const float fx = sx - float(x0), fy = sy - float(y0);
        v = glm::mix(glm::mix(texel(t, x0, y0), texel(t, x1, y0), fx),
                     glm::mix(texel(t, x0, y1), texel(t, x1, y1), fx), fy);
      }
      const size_t o = (size_t(y) * width + x) * 4;
      for (int c = 0; c < 4; ++c) {
        const float clamped = std::clamp(v[c], 0.0f, 1.0f);
        if (bits == 16) {
          const uint16_t q = uint16_t(std::lround(clamped * 65535.0f));
          std::memcpy(out + (o + size_t(c)) * 2, &q, 2);
        } else {
          out[o + size_t(c)] = uint8_t(std::lround(clamped * 255.0f));
        }
      }
    }
  }
}

}  // namespace

void GpuScene::upload_textures(const Scene& scene) {
  scene_textures_ = scene.textures.size();
  srgb_layer_.assign(scene.textures.size(), -1);
  linear_layer_.assign(scene.textures.size(), -1);
  for (const Texture& t : scene.textures) {
    const size_t expected = size_t(t.width) * t.height * 4 * (t.bits == 16 ? 2 : 1);
    if (t.width == 0 || t.height == 0 || (t.bits != 8 && t.bits != 16) ||
        t.pixels.size() != expected) {
      throw SceneError(scene.source + ": textures \"" + t.name + "\": expected " +
                       std::to_string(expected) + " bytes of 8- or 16-bit RGBA pixels, got " +
                       std::to_string(t.pixels.size()));
    }
  }
  // Which textures each array holds follows from the slots that use them, so a texture used
  // both ways lands in both.
  std::vector<int> srgb_members, linear_members;
  auto assign = [&](int tex, bool srgb) {
    if (tex < 0 || tex >= static_cast<int>(scene.textures.size())) return;
    auto& layer = srgb ? srgb_layer_ : linear_layer_;
    auto& members = srgb ? srgb_members : linear_members;
    if (layer[size_t(tex)] >= 0) return;
    layer[size_t(tex)] = static_cast<int32_t>(members.size());
    members.push_back(tex);
  };
  for (const Material& m : scene.materials) {
    assign(m.base_color_tex, true);
    assign(m.emissive_tex, true);
    assign(m.metallic_roughness_tex, false);
    assign(m.normal_tex, false);
    assign(m.occlusion_tex, false);
  }
  texture_sampler_ = context_->sampler(gpu::SamplerKind::SceneTexture);
  auto build = [&](const std::vector<int>& members, bool srgb) {
    uint32_t width = 1, height = 1, bits = 8;
    for (int tex : members) {
      const Texture& t = scene.textures[size_t(tex)];
      width = std::max(width, std::min(t.width, kMaxLayerSize));
      height = std::max(height, std::min(t.height, kMaxLayerSize));
      if (t.bits == 16 && !srgb) bits = 16;  // there is no 16-bit sRGB format
    }
    const uint32_t layers = std::max<uint32_t>(1, uint32_t(members.size()));
    const size_t layer_bytes = size_t(width) * height * 4 * (bits / 8);
    std::vector<uint8_t> pixels(layer_bytes * layers, 0xff);  // no members: one white layer
    for (size_t l = 0; l < members.size(); ++l) {
      resample(scene.textures[size_t(members[l])], width, height, bits,
               pixels.data() + l * layer_bytes);
    }
    gpu::ImageDesc desc;
    desc.format = bits == 16 ? VK_FORMAT_R16G16B16A16_UNORM
                  : srgb     ? VK_FORMAT_R8G8B8A8_SRGB
                             : VK_FORMAT_R8G8B8A8_UNORM;
    desc.extent = {width, height, 1};
    desc.mip_levels = 0;  // full chain
    desc.array_layers = layers;
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    desc.name = srgb ? "scene.textures_srgb" : "scene.textures_linear";
    auto image = std::make_unique<gpu::Image>(*context_, desc);
    if (!image->can_generate_mips()) {
      desc.mip_levels = 1;  // this device cannot blit the format: sample mip 0 only
      image = std::make_unique<gpu::Image>(*context_, desc);
    }
    image->upload(pixels.data(), pixels.size(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                  desc.mip_levels != 1);
    return image;
  };
  srgb_array_ = build(srgb_members, true);
  linear_array_ = build(linear_members, false);
  // Own 2D_ARRAY views: gpu::Image::view() is plain 2D for single-layer images.
  for (auto [image, view] :
       {std::pair{srgb_array_.get(), &srgb_view_}, std::pair{linear_array_.get(), &linear_view_}}) {
    VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    info.image = image->handle();
    info.viewType = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
    info.format = image->format();
    info.subresourceRange = image->range();
    gpu::check(vkCreateImageView(context_->device(), &info, nullptr, view),
               "vkCreateImageView (scene texture array)");
  }
}

void GpuScene::build_instances(const Scene& scene, std::vector<GpuInstance>& out) const {
  const std::vector<Instance> instances = scene.instances();
  out.clear();
  for (const Instance& instance : instances) {
    const Primitive& primitive =
        scene.meshes[size_t(instance.mesh)].primitives[size_t(instance.primitive)];
    GpuInstance g{};
    g.world = instance.world;
    const glm::mat3 linear(instance.world);
    // A singular matrix (zero scale) has no inverse; its normals do not matter then.
    const float det = glm::determinant(linear);
    g.normal_matrix = std::abs(det) > 1e-30f && std::isfinite(det)
                          ? glm::mat4(glm::transpose(glm::inverse(linear)))
                          : glm::mat4(1.0f);
    g.material = primitive.material >= 0 && primitive.material < int(scene.materials.size())
                     ? uint32_t(primitive.material)
                     : default_material_;
    g.flags = instance.mirrored ? kInstanceMirrored : 0u;
    out.push_back(g);
  }
}

void GpuScene::build_lights(const Scene& scene, std::vector<GpuLight>& out) const {
  out.clear();
  for (size_t i = 0; i < scene.lights.size(); ++i)
    out.push_back(to_gpu_light(scene.lights[i], int(i)));
}

void GpuScene::upload_lights() {
  std::vector<uint8_t> bytes(lights_->size(), 0);
  GpuLightHeader header{};
  header.count = static_cast<uint32_t>(gpu_lights_.size());
  std::memcpy(bytes.data(), &header, sizeof(header));
  if (!gpu_lights_.empty()) {
    std::memcpy(bytes.data() + sizeof(header), gpu_lights_.data(),
                gpu_lights_.size() * sizeof(GpuLight));
  }
  lights_->upload(bytes.data(), bytes.size());
}

void GpuScene::create_descriptors() {
  // Draws: opaque and masked first, then blended; each references its instance.
  draws_.clear();
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t i = 0; i < cpu_instances_.size(); ++i) {
      const Instance& instance = cpu_instances_[i];
      const GpuInstance& g = gpu_instances_[i];
      const GpuMaterial& material = gpu_materials_[g.material];
      const bool blend = material.alpha_mode == uint32_t(AlphaMode::Blend);
      if ((pass == 1) != blend) continue;
      const PrimitiveRange& range = ranges_[size_t(instance.mesh)][size_t(instance.primitive)];
      if (range.index_count == 0) continue;
      Draw draw{};
      draw.first_index = instance.mirrored && range.flipped_first_index != UINT32_MAX
                             ? range.flipped_first_index
                             : range.first_index;
      draw.index_count = range.index_count;
      draw.vertex_offset = range.vertex_offset;
      draw.instance = static_cast<uint32_t>(i);
      draw.material = g.material;
      draw.double_sided = material.double_sided != 0;
      draw.blend = blend;
      draws_.push_back(draw);
    }
  }

  VkDevice device = context_->device();
  VkDescriptorSetLayoutBinding bindings[5] = {};
  for (uint32_t b = 0; b < 5; ++b) {
    bindings[b].binding = b;
    bindings[b].descriptorType =
        b < 3 ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    bindings[b].descriptorCount = 1;
    bindings[b].stageFlags = VK_SHADER_STAGE_ALL;
  }
  VkDescriptorSetLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  layout_info.bindingCount = 5;
  layout_info.pBindings = bindings;
  gpu::check(vkCreateDescriptorSetLayout(device, &layout_info, nullptr, &set_layout_),
             "vkCreateDescriptorSetLayout (scene set)");

  const VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3},
                                         {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2}};
  VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = 2;
  pool_info.pPoolSizes = sizes;
  gpu::check(vkCreateDescriptorPool(device, &pool_info, nullptr, &pool_),
             "vkCreateDescriptorPool (scene set)");
  VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  alloc.descriptorPool = pool_;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &set_layout_;
  gpu::check(vkAllocateDescriptorSets(device, &alloc, &set_),
             "vkAllocateDescriptorSets (scene set)");
  context_->set_debug_name(VK_OBJECT_TYPE_DESCRIPTOR_SET, uint64_t(set_), "scene.set");

  const VkDescriptorBufferInfo buffers[3] = {{materials_->handle(), 0, VK_WHOLE_SIZE},
                                             {instances_->handle(), 0, VK_WHOLE_SIZE},
                                             {lights_->handle(), 0, VK_WHOLE_SIZE}};
  const VkDescriptorImageInfo images[2] = {
      {texture_sampler_, srgb_view_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
      {texture_sampler_, linear_view_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
  VkWriteDescriptorSet writes[5] = {};
  for (uint32_t b = 0; b < 5; ++b) {
    writes[b].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[b].dstSet = set_;
    writes[b].dstBinding = b;
    writes[b].descriptorType = bindings[b].descriptorType;
    writes[b].descriptorCount = 1;
    if (b < 3) {
      writes[b].pBufferInfo = &buffers[b];
    } else {
      writes[b].pImageInfo = &images[b - 3];
    }
  }
  vkUpdateDescriptorSets(device, 5, writes, 0, nullptr);
}

bool GpuScene::update(const Scene& scene) {
  const std::vector<Instance> instances = scene.instances();
  if (instances.size() != cpu_instances_.size() || scene.lights.size() != gpu_lights_.size()) {
    throw SceneError(scene.source + ": GpuScene::update: the scene's structure changed (" +
                     std::to_string(instances.size()) + " instances, " +
                     std::to_string(scene.lights.size()) + " lights; uploaded " +
                     std::to_string(cpu_instances_.size()) + " and " +
                     std::to_string(gpu_lights_.size()) + "); create a new GpuScene");
  }
  bool changed = false;
  std::vector<GpuInstance> new_instances;
  build_instances(scene, new_instances);
  if (std::memcmp(new_instances.data(), gpu_instances_.data(),
                  new_instances.size() * sizeof(GpuInstance)) != 0) {
    gpu_instances_ = std::move(new_instances);
    instances_->upload_vector(gpu_instances_);
    // A mirror that appeared or vanished switches the draw to the other winding.
    for (Draw& draw : draws_) {
      const Instance& now = instances[draw.instance];
      const PrimitiveRange& range = ranges_[size_t(now.mesh)][size_t(now.primitive)];
      draw.first_index = now.mirrored && range.flipped_first_index != UINT32_MAX
                             ? range.flipped_first_index
                             : range.first_index;
    }
    cpu_instances_ = instances;
    changed = true;
  }
  std::vector<GpuLight> new_lights;
  build_lights(scene, new_lights);
  if (std::memcmp(new_lights.data(), gpu_lights_.data(), new_lights.size() * sizeof(GpuLight)) !=
      0) {
    gpu_lights_ = std::move(new_lights);
    upload_lights();
    changed = true;
  }
  return changed;
}

std::vector<VkVertexInputAttributeDescription> GpuScene::vertex_attributes() {
  return {
      {0, 0, VK_FORMAT_R32G32B32_SFLOAT, uint32_t(offsetof(Vertex, position))},
      {1, 0, VK_FORMAT_R32G32B32_SFLOAT, uint32_t(offsetof(Vertex, normal))},
      {2, 0, VK_FORMAT_R32G32B32A32_SFLOAT, uint32_t(offsetof(Vertex, tangent))},
      {3, 0, VK_FORMAT_R32G32_SFLOAT, uint32_t(offsetof(Vertex, uv))},
      {4, 0, VK_FORMAT_R32G32_SFLOAT, uint32_t(offsetof(Vertex, uv1))},
      {5, 0, VK_FORMAT_R32G32B32A32_SFLOAT, uint32_t(offsetof(Vertex, color))},
  };
}

VkVertexInputBindingDescription GpuScene::vertex_binding() {
  return {0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
}

void GpuScene::record_draws(VkCommandBuffer cmd,
                            const std::function<bool(const Draw&)>& keep) const {
  if (draws_.empty()) return;
  VkDeviceSize offset = 0;
  VkBuffer vertex_buffer = vertices_->handle();
  vkCmdBindVertexBuffers(cmd, 0, 1, &vertex_buffer, &offset);
  vkCmdBindIndexBuffer(cmd, indices_->handle(), 0, VK_INDEX_TYPE_UINT32);
  for (const Draw& draw : draws_) {
    if (keep && !keep(draw)) continue;
    vkCmdDrawIndexed(cmd, draw.index_count, 1, draw.first_index, draw.vertex_offset, draw.instance);
  }
}

}  // namespace voxgi::scene
