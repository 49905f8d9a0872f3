// The reference path tracer: a progressive, unbiased estimate of the rendering equation over
// the scene's BVH with the same glTF BRDF, light units and falloffs as the real-time passes,
// so that every GI technique can be measured against it (and it against offline references).
//
// Samples accumulate in a persistent image across frames; the running sums start over when
// the camera, the lights, the geometry or a parameter changes. Each (pixel, sample index)
// pair always draws the same random numbers, so a run is reproducible.

#include <algorithm>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/gpu/context.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/gpu/shader_compiler.hpp"
#include "engine/graph/pass.hpp"
#include "engine/graph/pass_helpers.hpp"
#include "engine/scene/gpu_bvh.hpp"
#include "engine/scene/gpu_scene.hpp"
#include "passes/reference/passes.hpp"

namespace voxgi::passes::reference {
namespace {

using graph::Access;
using graph::ResourceKind;

constexpr uint32_t kTile = 8;
constexpr uint32_t kAccumulationLayers = 5;
constexpr uint32_t kFlagLambert = 1;
constexpr uint32_t kFlagPixelJitter = 2;
constexpr uint32_t kFlagDeferredLayers = 4;
constexpr uint32_t kFlagSingleSided = 8;

// Mirrors the push-constant block of shaders/reference/path_trace.comp.
struct PathTracePush {
  float origin[4];
  uint32_t width;
  uint32_t height;
  uint32_t sample_base;
  uint32_t samples;
  uint32_t max_depth;
  uint32_t rr_start;
  uint32_t flags;
  uint32_t node_count;
  uint32_t emitter_count;
  float first_bounce_distance;
  float first_bounce_sin2_min;
  float first_bounce_sin2_max;
};
static_assert(sizeof(PathTracePush) == 64);

// A 2D_ARRAY view of all mips and layers of one of the scene's texture arrays
// (gpu::Image::view() is plain 2D when the array has a single layer).
struct ArrayView {
  VkDevice device = VK_NULL_HANDLE;
  VkImageView handle = VK_NULL_HANDLE;
  ArrayView() = default;
  ArrayView(const ArrayView&) = delete;
  ArrayView& operator=(const ArrayView&) = delete;
  ~ArrayView() { destroy(); }
  void destroy() {
    if (handle != VK_NULL_HANDLE) vkDestroyImageView(device, handle, nullptr);
    handle = VK_NULL_HANDLE;
  }
  void create(gpu::Context& context, const gpu::Image& image) {
    destroy();
    device = context.device();
    VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    info.image = image.handle();
    info.viewType = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
    info.format = image.format();
    info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, VK_REMAINING_MIP_LEVELS, 0,
                             VK_REMAINING_ARRAY_LAYERS};
    if (vkCreateImageView(device, &info, nullptr, &handle) != VK_SUCCESS) {
      handle = VK_NULL_HANDLE;
      throw std::runtime_error("reference.path_tracer: cannot create a view of the scene textures");
    }
  }
};

class PathTracerPass final : public graph::Pass {
 public:
  void setup(graph::PassContext& ctx) override {
    ctx.scene_bvh();  // built now rather than while the first frame records

    gpu::ShaderRequest request;
    request.path = "reference/path_trace.comp";
    // Alpha tests inside the traversal are costly; compile them only where a material needs
    // them.
    bool has_alpha = false;
    for (const scene::Material& m : ctx.scene().materials) {
      has_alpha = has_alpha || m.alpha_mode != scene::AlphaMode::Opaque;
    }
    request.defines = {{"HAS_ALPHA", has_alpha ? "1" : "0"}};
    gpu::PipelineLayoutDesc layout;
    layout.bindings = {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                       {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                       {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                       {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                       {4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                       {5, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                       {6, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                       {7, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                       {8, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                       {9, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                       {10, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT},
                       {11, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT},
                       {12, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT}};
    layout.extra_set_layouts = {ctx.gpu_scene().set_layout()};
    layout.push_constant_size = sizeof(PathTracePush);
    layout.push_constant_stages = VK_SHADER_STAGE_COMPUTE_BIT;
    pipeline_.emplace(ctx.gpu(), ctx.shaders().compile(request), layout, ctx.pass_name());
    srgb_view_.create(ctx.gpu(), ctx.gpu_scene().srgb_textures());
    linear_view_.create(ctx.gpu(), ctx.gpu_scene().linear_textures());
    samples_done_ = 0;
  }

  void execute(graph::PassContext& ctx) override {
    const graph::FrameInfo& frame = ctx.frame();
    // Refit by the scene service when instances moved since it last saw them.
    const scene::GpuBvh& bvh = ctx.scene_bvh();
    if (frame.first_frame || frame.camera_changed || frame.lights_changed ||
        frame.geometry_changed || ctx.params_changed()) {
      samples_done_ = 0;
    }
    const uint32_t max_samples = static_cast<uint32_t>(ctx.integer("max_samples"));
    uint32_t samples = static_cast<uint32_t>(ctx.integer("samples_per_frame"));
    if (max_samples > 0)
      samples = samples_done_ >= max_samples ? 0 : std::min(samples, max_samples - samples_done_);

    const graph::BoundResource& accumulation = ctx.resource("accumulation");
    const graph::BoundResource& linear = ctx.resource("linear");
    const graph::BoundResource& direct = ctx.resource("direct");
    const graph::BoundResource& indirect = ctx.resource("indirect");
    const graph::BoundResource& variance = ctx.resource("variance");
    const graph::BoundResource& indirect_variance = ctx.resource("indirect_variance");
    const VkExtent3D extent = linear.info->extent;

    VkCommandBuffer cmd = ctx.cmd();
    const VkSampler sampler = ctx.gpu().sampler(gpu::SamplerKind::LinearRepeat);
    const VkImageView srgb_textures = srgb_view_.handle;
    const VkImageView linear_textures = linear_view_.handle;
    pipeline_->bind(cmd);
    gpu::DescriptorWriter()
        .uniform_buffer(0, *frame.uniform_buffer)
        .storage_buffer(1, bvh.nodes())
        .storage_buffer(2, bvh.triangles())
        .storage_buffer(3, bvh.shading())
        .storage_buffer(4, bvh.emitters())
        .storage_image(5, accumulation.view, accumulation.layout)
        .storage_image(6, linear.view, linear.layout)
        .storage_image(7, direct.view, direct.layout)
        .storage_image(8, indirect.view, indirect.layout)
        .storage_image(9, variance.view, variance.layout)
        // The scene's texture arrays with a plain bilinear sampler (see path_trace.comp).
        .sampled_image(10, srgb_textures, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, sampler)
        .sampled_image(11, linear_textures, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, sampler)
        .storage_image(12, indirect_variance.view, indirect_variance.layout)
        .push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout());
    VkDescriptorSet scene_set = ctx.gpu_scene().descriptor_set();
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout(), 1, 1,
                            &scene_set, 0, nullptr);

    PathTracePush push{};
    const glm::vec3 origin = bvh.origin();
    push.origin[0] = origin.x;
    push.origin[1] = origin.y;
    push.origin[2] = origin.z;
    push.width = extent.width;
    push.height = extent.height;
    push.sample_base = samples_done_;
    push.samples = samples;
    push.max_depth = static_cast<uint32_t>(ctx.integer("max_depth"));
    push.rr_start = static_cast<uint32_t>(ctx.integer("rr_start"));
    push.flags = (ctx.flag("lambert") ? kFlagLambert : 0u) |
                 (ctx.flag("pixel_jitter") ? kFlagPixelJitter : 0u) |
                 (ctx.flag("deferred_layers") ? kFlagDeferredLayers : 0u) |
                 (ctx.flag("single_sided") ? kFlagSingleSided : 0u);
    push.node_count = bvh.node_count();
    push.emitter_count = bvh.emitter_count();
    push.first_bounce_distance = static_cast<float>(ctx.number("first_bounce_distance"));
    push.first_bounce_sin2_min = static_cast<float>(ctx.number("first_bounce_sin2_min"));
    push.first_bounce_sin2_max = static_cast<float>(ctx.number("first_bounce_sin2_max"));
    pipeline_->push_constants(cmd, push);
    vkCmdDispatch(cmd, graph::workgroups(extent.width, kTile),
                  graph::workgroups(extent.height, kTile), 1);
    samples_done_ += samples;
  }

 private:
  std::optional<gpu::ComputePipeline> pipeline_;
  ArrayView srgb_view_, linear_view_;
  uint32_t samples_done_ = 0;
};

graph::SlotSpec image_output(const char* name, Access access, std::vector<VkFormat> formats,
                             const char* doc) {
  return {name,
          graph::kinds(ResourceKind::Image2D),
          access,
          graph::kStageCompute,
          std::move(formats),
          false,
          doc};
}

void validate_path_tracer(graph::PassCheck& check) {
  const graph::ResourceInfo& accumulation = check.info("accumulation");
  if (accumulation.array_layers < kAccumulationLayers) {
    check.slot_error(
        "accumulation",
        "resource '" + accumulation.name + "' needs " + std::to_string(kAccumulationLayers) +
            " layers (running sums of radiance, direct, indirect and their squares), has " +
            std::to_string(accumulation.array_layers));
  }
  const VkExtent3D linear = check.info("linear").extent;
  if (accumulation.extent.width < linear.width || accumulation.extent.height < linear.height) {
    check.slot_error("accumulation",
                     "resource '" + accumulation.name + "' is smaller than the 'linear' output");
  }
}

}  // namespace

void register_path_tracer(graph::Registry& registry) {
  const std::vector<VkFormat> hdr = {VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT};
  graph::PassTypeInfo info;
  info.type = "reference.path_tracer";
  info.doc =
      "Progressive path tracer over a BVH with the glTF BRDF, light sampling with MIS and "
      "Russian roulette: the ground truth GI techniques are measured against";
  info.outputs = {
      image_output("accumulation", Access::StorageReadWrite, {VK_FORMAT_R32G32B32A32_SFLOAT},
                   "persistent running sums, 5 layers: radiance (w: samples), direct, "
                   "indirect, squared radiance, squared indirect"),
      image_output("linear", Access::StorageWrite, hdr, "mean radiance (direct + indirect)"),
      image_output("direct", Access::StorageWrite, hdr,
                   "emission seen directly plus light after one reflection"),
      image_output("indirect", Access::StorageWrite, hdr,
                   "light after two or more reflections: what GI techniques approximate"),
      image_output("variance", Access::StorageWrite, hdr,
                   "per-channel variance of the mean radiance (w: samples so far)"),
      image_output("indirect_variance", Access::StorageWrite, hdr,
                   "per-channel variance of the mean indirect light (w: samples so far): the "
                   "reference's own noise where GI techniques are measured against it"),
  };
  info.params = {
      {"samples_per_frame",
       graph::ParamType::Int,
       1.0,
       1.0,
       256.0,
       {},
       "paths per pixel added each frame",
       true},
      {"max_depth",
       graph::ParamType::Int,
       17.0,
       0.0,
       64.0,
       {},
       "most reflections a path makes (0: emission only, 1: direct light; 17 matches the "
       "offline references' 16 bounces)",
       true},
      {"rr_start",
       graph::ParamType::Int,
       5.0,
       0.0,
       64.0,
       {},
       "reflections before Russian roulette may end a path (unbiased either way)",
       true},
      {"lambert",
       graph::ParamType::Bool,
       0.0,
       0.0,
       1.0,
       {},
       "override every material by a Lambertian of its base colour",
       true},
      {"deferred_layers",
       graph::ParamType::Bool,
       0.0,
       0.0,
       1.0,
       {},
       "split direct/indirect as deferred lighting + voxel GI do (direct: emission seen and "
       "punctual lights at the first hit; emissive surfaces reach max_depth - 1 reflections), "
       "for like-with-like comparisons of GI techniques",
       true},
      {"single_sided",
       graph::ParamType::Bool,
       0.0,
       0.0,
       1.0,
       {},
       "treat glTF single-sided materials (doubleSided false) as the rasterised passes do: "
       "camera rays pass through their faces seen from behind their winding, which the "
       "G-buffer culls, and any other ray that meets one from the side its vertex normals turn "
       "away from stops there with no light, as voxels light only the side their normals face "
       "(off: both faces shaded, as Cycles renders glTF)",
       true},
      {"pixel_jitter",
       graph::ParamType::Bool,
       1.0,
       0.0,
       1.0,
       {},
       "spread each pixel's rays over its area (a 1-pixel box filter); off: pixel centres, "
       "to compare pixel by pixel with rasterised passes",
       true},
      {"first_bounce_distance",
       graph::ParamType::Float,
       0.0,
       0.0,
       1e6,
       {},
       "leave out the light of first reflections farther than this from the visible surface "
       "(scene units; 0: no limit), by light and BSDF sampling alike: the near part of a "
       "reference, to set against cones of the same cone_trace.max_distance",
       true},
      {"first_bounce_sin2_min",
       graph::ParamType::Float,
       0.0,
       0.0,
       1.0,
       {},
       "keep only first reflections whose direction's sin^2 to the visible surface's normal is "
       "at least this (with first_bounce_sin2_max: a band of the cosine-weighted hemisphere, "
       "where equal steps hold equal weight, as the rings of diffuse cones do)",
       true},
      {"first_bounce_sin2_max",
       graph::ParamType::Float,
       1.0,
       0.0,
       1.0,
       {},
       "keep only first reflections whose direction's sin^2 to the visible surface's normal is "
       "below this (1: up to the horizon); a band no wider than 0 keeps nothing",
       true},
      {"max_samples",
       graph::ParamType::Int,
       0.0,
       0.0,
       1e7,
       {},
       "stop adding samples after this many per pixel (0: never)",
       true},
  };
  // The running sums: the mean's extent, one layer per sum.
  graph::set_size_rule(info, "accumulation", [](const graph::SizeQuery& query) {
    graph::DerivedSize size = graph::same_layout_as("linear")(query);
    size.layers = kAccumulationLayers;
    return size;
  });
  info.validate = validate_path_tracer;
  registry.add(std::move(info), [] { return std::make_unique<PathTracerPass>(); });
}

}  // namespace voxgi::passes::reference
