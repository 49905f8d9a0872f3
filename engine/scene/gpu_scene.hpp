#pragma once
// The scene on the GPU: one vertex and one index buffer for all primitives, material /
// instance / light storage buffers, textures, and the descriptor set (set 1 of scene-drawing
// pipelines) that shaders/lib/scene.glsl declares.
//
// Textures live in two 2D array textures, one sRGB (base colour, emissive) and one linear
// (metallic-roughness, normal, occlusion), every texture resampled to the array's layer size.
// Arrays instead of descriptor arrays because the baseline device (lavapipe) has neither
// descriptor indexing nor dynamic indexing of sampler arrays, and 32 samplers per stage; a
// layer index is an ordinary coordinate, valid even when it differs per pixel.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/image.hpp"
#include "engine/scene/scene.hpp"

namespace voxgi::gpu {
class Context;
}

namespace voxgi::scene {

class GpuBvh;
struct SceneBvh;

// std430 mirrors of the structs in shaders/lib/scene.glsl. Keep them in step.
struct GpuMaterial {
  glm::vec4 base_color;
  glm::vec3 emissive;
  float metallic;
  float roughness;
  float normal_scale;
  float occlusion_strength;
  float alpha_cutoff;
  // Layer in the sRGB array (base colour, emissive) or the linear array (the others); -1: none.
  int32_t base_color_tex;
  int32_t metallic_roughness_tex;
  int32_t normal_tex;
  int32_t occlusion_tex;
  int32_t emissive_tex;
  uint32_t alpha_mode;  // 0 opaque, 1 mask, 2 blend
  uint32_t double_sided;
  // Bit per texture slot (0 base colour, 1 metallic-roughness, 2 normal, 3 occlusion,
  // 4 emissive): clamp-to-edge instead of repeat.
  uint32_t clamp_mask;
  // Per slot two rows of its texture-coordinate transform (TextureMapping::matrix_rows); the
  // first row's w is the TEXCOORD set (0 or 1).
  glm::vec4 uv_rows[10];
};
static_assert(sizeof(GpuMaterial) == 240);

inline constexpr uint32_t kInstanceMirrored = 1;  // GpuInstance::flags: det(world) < 0

struct GpuInstance {
  glm::mat4 world;
  glm::mat4 normal_matrix;  // inverse transpose of world
  uint32_t material;
  // kInstanceMirrored: the world matrix mirrors; multiply the tangent's w by -1 after the
  // transform. (The winding is already fixed by the draw's index range.)
  uint32_t flags;
  uint32_t pad[2];
};
static_assert(sizeof(GpuInstance) == 144);

enum class GpuLightType : uint32_t { Directional = 0, Point = 1, Spot = 2 };

struct GpuLight {
  glm::vec3 position;
  uint32_t type;        // GpuLightType
  glm::vec3 direction;  // where the light points (unit)
  float range;          // 0 = infinite
  glm::vec3 radiance;   // color × intensity (cd for point/spot, lux for directional)
  // KHR_lights_punctual cone: clamp(cos_angle * spot_scale + spot_offset, 0, 1)^2; point and
  // directional lights get scale 0, offset 1.
  float spot_scale;
  float spot_offset;
  int32_t shadow_index;  // = light index
  float pad[2];
};
static_assert(sizeof(GpuLight) == 64);

struct GpuLightHeader {
  uint32_t count;
  uint32_t pad[3];
};

GpuLight to_gpu_light(const Light& light, int index);
GpuMaterial to_gpu_material(const Material& material);

class GpuScene {
 public:
  // Binding numbers of set 1.
  static constexpr uint32_t kMaterialsBinding = 0;
  static constexpr uint32_t kInstancesBinding = 1;
  static constexpr uint32_t kLightsBinding = 2;
  static constexpr uint32_t kSrgbTexturesBinding = 3;    // sampler2DArray
  static constexpr uint32_t kLinearTexturesBinding = 4;  // sampler2DArray
  // Layers are resampled to at most this size on each side.
  static constexpr uint32_t kMaxLayerSize = 2048;

  struct Draw {
    uint32_t first_index;  // into indices(); mirrored instances use a winding-swapped copy
    uint32_t index_count;
    int32_t vertex_offset;
    uint32_t instance;  // index into the instance buffer; pass it as firstInstance
    uint32_t material;  // index into the material buffer (the last one is the default)
    bool double_sided;
    bool blend;
  };

  // Uploads everything (waits for the queue). Empty scenes work: every buffer holds at least
  // one element and each texture array at least one 1×1 white layer.
  GpuScene(gpu::Context& context, const Scene& scene);
  ~GpuScene();
  GpuScene(const GpuScene&) = delete;
  GpuScene& operator=(const GpuScene&) = delete;

  // After Scene::animate(): re-uploads instance transforms and lights that changed and
  // returns whether anything did. The scene must have the same structure (meshes, nodes,
  // lights) as at construction; call it between frames, not while one using it is in flight.
  bool update(const Scene& scene);

  // The scene's BVH on the GPU (shaders/lib/bvh_traversal.glsl), the one every pass that traces
  // rays binds. Built on first use and refit here when the scene's instances moved since it was
  // built or last refit, so the passes and graphs sharing this GpuScene build and refit it
  // once. `scene` is the scene this GpuScene was made from, as it is now. It uploads and waits
  // for the queue: call it from setup() or execute(), or between frames.
  const GpuBvh& bvh(const Scene& scene);
  // Whether bvh() has built it (tests: a scene nobody traces has none).
  bool has_bvh() const { return bvh_ != nullptr; }

  const gpu::Buffer& vertices() const { return *vertices_; }
  const gpu::Buffer& indices() const { return *indices_; }
  const gpu::Buffer& materials() const { return *materials_; }
  const gpu::Buffer& instances() const { return *instances_; }
  const gpu::Buffer& lights() const { return *lights_; }
  // Opaque and masked draws first, then blended ones.
  const std::vector<Draw>& draws() const { return draws_; }
  // Binds vertices() and indices() and records one indexed draw per entry of draws() that
  // `keep` accepts (all when it is empty), with the pipeline and descriptors already bound.
  void record_draws(VkCommandBuffer cmd,
                    const std::function<bool(const Draw&)>& keep = nullptr) const;
  VkDescriptorSetLayout set_layout() const { return set_layout_; }
  VkDescriptorSet descriptor_set() const { return set_; }
  uint32_t light_count() const { return static_cast<uint32_t>(gpu_lights_.size()); }
  uint32_t texture_count() const { return static_cast<uint32_t>(scene_textures_); }
  const gpu::Image& srgb_textures() const { return *srgb_array_; }
  const gpu::Image& linear_textures() const { return *linear_array_; }
  uint32_t instance_count() const { return static_cast<uint32_t>(gpu_instances_.size()); }
  const std::vector<GpuMaterial>& gpu_materials() const { return gpu_materials_; }
  const std::vector<GpuInstance>& gpu_instances() const { return gpu_instances_; }
  const std::vector<GpuLight>& gpu_lights() const { return gpu_lights_; }

  // Locations 0 position (vec3), 1 normal (vec3), 2 tangent (vec4), 3 uv (vec2); binding 0.
  static std::vector<VkVertexInputAttributeDescription> vertex_attributes();
  static VkVertexInputBindingDescription vertex_binding();

 private:
  void upload_geometry(const Scene& scene);
  void upload_textures(const Scene& scene);  // before upload_materials: it assigns layers
  void upload_materials(const Scene& scene);
  void build_instances(const Scene& scene, std::vector<GpuInstance>& out) const;
  void build_lights(const Scene& scene, std::vector<GpuLight>& out) const;
  void upload_lights();
  void create_descriptors();
  void release_descriptors();  // and the texture array views

  gpu::Context* context_;
  std::unique_ptr<gpu::Buffer> vertices_, indices_, materials_, instances_, lights_;
  std::unique_ptr<gpu::Image> srgb_array_, linear_array_;
  VkSampler texture_sampler_ = VK_NULL_HANDLE;
  VkImageView srgb_view_ = VK_NULL_HANDLE, linear_view_ = VK_NULL_HANDLE;
  size_t scene_textures_ = 0;
  // Scene texture index → layer in the sRGB / linear array (-1: not in that array).
  std::vector<int32_t> srgb_layer_, linear_layer_;
  uint32_t default_material_ = 0;

  // Per primitive (mesh, primitive): offsets into the shared buffers.
  struct PrimitiveRange {
    uint32_t first_index = 0;
    uint32_t flipped_first_index = UINT32_MAX;  // winding-swapped copy, when one was needed
    uint32_t index_count = 0;
    int32_t vertex_offset = 0;
  };
  std::vector<std::vector<PrimitiveRange>> ranges_;
  std::unique_ptr<SceneBvh> bvh_;  // built by bvh() on first use
  std::vector<Instance> cpu_instances_;
  std::vector<GpuMaterial> gpu_materials_;
  std::vector<GpuInstance> gpu_instances_;
  std::vector<GpuLight> gpu_lights_;
  std::vector<Draw> draws_;

  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace voxgi::scene
