// vct.cone_trace (indirect diffuse + ambient occlusion) and vct.cone_trace_specular (one
// glossy cone): cone tracing through the filtered volumes (shaders/contracts/cone_trace.glsl) per
// G-buffer pixel, at full resolution or at half resolution followed by a depth- and
// normal-aware upsample through the graph-provided scratch image `half_res`. The diffuse
// gather's interleaved average (parameter `interleave`) is a dispatch of its own over an
// image the pass keeps, so that its windows cross workgroups.

#include <cmath>
#include <memory>
#include <optional>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/gpu/sync.hpp"
#include "engine/graph/pass.hpp"
#include "passes/contracts/gbuffer.hpp"
#include "passes/contracts/voxel_clipmap.hpp"
#include "passes/vct/passes.hpp"
#include "passes/vct/vct_pipeline.hpp"

namespace voxgi::passes::vct {
namespace {

constexpr double kRadians = 3.14159265358979323846 / 180.0;

struct TracePush {
  uint32_t width;
  uint32_t height;
  int32_t diffuse_cones;
  float step_factor;
  float max_distance;
  float ao_falloff;
  float normal_offset;
  float start_offset;
  float shadow_tan_half_angle;
  int32_t lanes;
  int32_t interleave;
  int32_t lane_rows;  // VCT_LANE_ROWS_* of contracts/cone_trace.glsl
};

// contracts/cone_trace.glsl's VCT_LANE_ROWS_APERTURE and VCT_LANE_ROWS_CELL.
constexpr int32_t kLaneRowsAperture = 0;
constexpr int32_t kLaneRowsCell = 1;

struct InterleavePush {
  uint32_t width;
  uint32_t height;
  int32_t interleave;
};

struct UpsamplePush {
  uint32_t width;
  uint32_t height;
  float depth_tolerance;
  float normal_power;
};

// Storage-image format qualifier of the single-channel outputs (AO, shadow).
const char* scalar_format_qualifier(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R8_UNORM:
      return "r8";
    case VK_FORMAT_R16_SFLOAT:
      return "r16f";
    case VK_FORMAT_R8G8B8A8_UNORM:
      return "rgba8";
    default:
      return "rgba16f";
  }
}

// Bindings of trace.comp and upsample.comp (set 0).
constexpr uint32_t kBindingClipmapInfo = 0;
constexpr uint32_t kBindingVolumes = 1;
constexpr uint32_t kBindingFrame = 2;
constexpr uint32_t kBindingGbuffer = 3;  // base colour, normal, material, depth: 3..6
constexpr uint32_t kBindingResult = 7;
constexpr uint32_t kBindingAo = 8;
constexpr uint32_t kBindingScratch = 9;
constexpr uint32_t kBindingShadow = 10;
constexpr uint32_t kBindingFacing = 11;

class ConeTracePass final : public graph::Pass {
 public:
  explicit ConeTracePass(bool specular) : specular_(specular) {}

  void setup(graph::PassContext& ctx) override {
    anisotropic_ = bound_filtered_volumes(ctx) == FilteredVolumes::Anisotropic;
    if (!sampler_) sampler_ = std::make_unique<contracts::VolumeSampler>(ctx.gpu());
    half_ = ctx.choice("resolution") == "half";
    has_ao_ = !specular_ && ctx.has("ao");
    has_shadow_ = !specular_ && ctx.has("shadow");
    facing_ = ctx.has("voxel_normal");
    front_light_ = anisotropic_ && contracts::front_light_bound(ctx);
    std::vector<gpu::ShaderDefine> defines = {
        {"SPECULAR", specular_ ? "1" : "0"},
        {"VCT_ANISOTROPIC", anisotropic_ ? "1" : "0"},
        {"HAS_AO", has_ao_ ? "1" : "0"},
        {"AO_FORMAT", has_ao_ ? scalar_format_qualifier(ctx.info("ao").format) : "r16f"},
        {"SHADOW_FORMAT",
         has_shadow_ ? scalar_format_qualifier(ctx.info("shadow").format) : "r16f"}};
    if (facing_) defines.push_back({"HAS_FACING", "1"});
    if (!specular_ && ctx.flag("specular_layer")) defines.push_back({"SPECULAR_LAYER", "1"});
    defines.push_back(contracts::front_light_define(front_light_));
    const char* volumes_slot =
        anisotropic_ ? contracts::kDirectionalSlots[0] : contracts::kFilteredSlot;
    const uint32_t levels = ctx.info(volumes_slot).clipmap_levels;
    defines.push_back(contracts::unwrapped_windows_define(levels));
    defines.push_back(contracts::clipmap_levels_define(levels));
    defines.push_back(contracts::refine_levels_define(ctx.integer("refine")));
    std::vector<gpu::Binding> gbuffer = {{kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 0}};
    for (uint32_t i = 0; i < 4; ++i) {
      gbuffer.push_back({kBindingGbuffer + i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
    }
    std::vector<gpu::Binding> volumes = {
        {kBindingClipmapInfo, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0},
        {kBindingVolumes, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0,
         contracts::volume_array_size(anisotropic_, front_light_)}};
    if (facing_) volumes.push_back({kBindingFacing, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
    const gpu::Binding result = {kBindingResult, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 0};
    const gpu::Binding storage_ao = {kBindingAo, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 0};
    const gpu::Binding storage_shadow = {kBindingShadow, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 0};

    // The shadow cone runs inside the main trace at full resolution, and in a full-resolution
    // dispatch of its own at half resolution (a shadow edge must not be upsampled away).
    const bool shadow_in_trace = has_shadow_ && !half_;
    std::vector<gpu::Binding> trace = gbuffer;
    trace.insert(trace.end(), volumes.begin(), volumes.end());
    trace.push_back(result);
    if (has_ao_ && !half_) trace.push_back(storage_ao);
    if (shadow_in_trace) trace.push_back(storage_shadow);
    std::vector<gpu::ShaderDefine> trace_defines = defines;
    trace_defines.push_back({"HALF", half_ ? "1" : "0"});
    trace_defines.push_back({"HAS_SHADOW", shadow_in_trace ? "1" : "0"});
    trace_.emplace(graph::make_pass_compute(ctx, "vct/trace.comp", trace, sizeof(TracePush),
                                            shadow_in_trace, trace_defines));

    shadow_.reset();
    if (has_shadow_ && half_) {
      std::vector<gpu::Binding> shadow = gbuffer;
      shadow.insert(shadow.end(), volumes.begin(), volumes.end());
      shadow.push_back(storage_shadow);
      std::vector<gpu::ShaderDefine> shadow_defines = defines;
      shadow_defines.push_back({"HAS_SHADOW", "1"});
      shadow_defines.push_back({"SHADOW_ONLY", "1"});
      shadow_.emplace(graph::make_pass_compute(ctx, "vct/trace.comp", shadow, sizeof(TracePush),
                                               true, shadow_defines));
    }

    // The interleaved average: from the pass's own image of per-pixel gathers to the result
    // (full resolution) or to `half_res` (half).
    interleave_.reset();
    if (!specular_) {
      std::vector<gpu::Binding> average = gbuffer;
      average.push_back(result);
      if (has_ao_ && !half_) average.push_back(storage_ao);
      average.push_back({kBindingScratch, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
      std::vector<gpu::ShaderDefine> average_defines = defines;
      average_defines.push_back({"HALF", half_ ? "1" : "0"});
      interleave_.emplace(graph::make_pass_compute(ctx, "vct/interleave.comp", average,
                                                   sizeof(InterleavePush), false, average_defines));
    }

    upsample_.reset();
    if (half_) {
      std::vector<gpu::Binding> upsample = gbuffer;
      upsample.push_back(result);
      upsample.push_back({kBindingScratch, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
      if (has_ao_) upsample.push_back(storage_ao);
      upsample_.emplace(graph::make_pass_compute(ctx, "vct/upsample.comp", upsample,
                                                 sizeof(UpsamplePush), false, defines));
    }
  }

  void execute(graph::PassContext& ctx) override {
    VkCommandBuffer cmd = ctx.cmd();
    const VkSampler nearest = ctx.gpu().sampler(gpu::SamplerKind::NearestClamp);
    const graph::BoundResource& result = ctx.resource(specular_ ? "specular" : "diffuse");

    auto bind_gbuffer = [&](gpu::DescriptorWriter& writer) {
      writer.uniform_buffer(kBindingFrame, *ctx.frame().uniform_buffer);
      const char* slots[] = {"base_color", "normal", "material", "depth"};
      for (uint32_t i = 0; i < 4; ++i) {
        const graph::BoundResource& r = ctx.resource(slots[i]);
        writer.sampled_image(kBindingGbuffer + i, r.view, r.layout, nearest);
      }
    };
    auto bind_volumes = [&](gpu::DescriptorWriter& writer) {
      writer.storage_buffer(kBindingClipmapInfo, *ctx.resource("clipmap_info").buffer);
      const VkSampler repeat = sampler_->handle();
      writer.image_array(kBindingVolumes, contracts::filtered_volume_images(ctx, anisotropic_,
                                                                            front_light_, repeat));
      if (facing_) {
        const graph::BoundResource& n = ctx.resource("voxel_normal");
        writer.sampled_image(kBindingFacing, n.view, n.layout, repeat);
      }
    };
    auto bind_storage = [&](gpu::DescriptorWriter& writer, uint32_t binding, const char* slot) {
      const graph::BoundResource& r = ctx.resource(slot);
      writer.storage_image(binding, r.view, r.layout);
    };
    auto push_for = [&](VkExtent3D e) {
      const double shadow_angle = specular_ ? 0.0 : ctx.number("shadow_cone_angle") * kRadians;
      const int32_t lane_rows =
          !specular_ && ctx.choice("lane_rows") == "cell" ? kLaneRowsCell : kLaneRowsAperture;
      return TracePush{e.width,
                       e.height,
                       specular_ ? 1 : ctx.integer("diffuse_cones"),
                       static_cast<float>(ctx.number("step_factor")),
                       contracts::cone_max_distance(ctx.number("max_distance")),
                       specular_ ? 0.0f : static_cast<float>(ctx.number("ao_falloff")),
                       static_cast<float>(ctx.number("normal_offset")),
                       static_cast<float>(ctx.number("start_offset")),
                       static_cast<float>(std::tan(shadow_angle)),
                       ctx.integer("lanes"),
                       specular_ ? 1 : ctx.integer("interleave"),
                       lane_rows};
    };

    const graph::BoundResource& traced = half_ ? ctx.resource("half_res") : result;
    const VkExtent3D traced_extent = traced.info->extent;
    const int interleave = specular_ ? 1 : ctx.integer("interleave");
    if (interleave > 1) prepare_gathers(ctx, traced_extent);
    {
      gpu::DescriptorWriter writer;
      bind_gbuffer(writer);
      bind_volumes(writer);
      if (interleave > 1) {
        writer.storage_image(kBindingResult, gathers_->view(), VK_IMAGE_LAYOUT_GENERAL);
      } else {
        writer.storage_image(kBindingResult, traced.view, traced.layout);
      }
      if (has_ao_ && !half_) bind_storage(writer, kBindingAo, "ao");
      if (has_shadow_ && !half_) bind_storage(writer, kBindingShadow, "shadow");
      const VkExtent3D e = traced_extent;
      trace_->bind(cmd);
      writer.push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, trace_->layout());
      if (has_shadow_ && !half_) graph::bind_scene_set(ctx, *trace_);
      trace_->push_constants(cmd, push_for(e));
      vkCmdDispatch(cmd, graph::workgroups(e.width, kTile), graph::workgroups(e.height, kTile), 1);
    }
    if (shadow_) {
      gpu::DescriptorWriter writer;
      bind_gbuffer(writer);
      bind_volumes(writer);
      bind_storage(writer, kBindingShadow, "shadow");
      const VkExtent3D e = ctx.info("shadow").extent;
      shadow_->bind(cmd);
      writer.push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, shadow_->layout());
      graph::bind_scene_set(ctx, *shadow_);
      shadow_->push_constants(cmd, push_for(e));
      vkCmdDispatch(cmd, graph::workgroups(e.width, kTile), graph::workgroups(e.height, kTile), 1);
    }
    if (interleave > 1) {
      order_gathers(cmd);
      gpu::DescriptorWriter writer;
      bind_gbuffer(writer);
      writer.storage_image(kBindingResult, traced.view, traced.layout);
      if (has_ao_ && !half_) bind_storage(writer, kBindingAo, "ao");
      writer.sampled_image(kBindingScratch, gathers_->view(), VK_IMAGE_LAYOUT_GENERAL, nearest);
      interleave_->bind(cmd);
      writer.push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, interleave_->layout());
      interleave_->push_constants(
          cmd, InterleavePush{traced_extent.width, traced_extent.height, interleave});
      vkCmdDispatch(cmd, graph::workgroups(traced_extent.width, kTile),
                    graph::workgroups(traced_extent.height, kTile), 1);
    }
    if (!half_) return;

    ctx.barrier_within_pass("half_res");
    gpu::DescriptorWriter writer;
    bind_gbuffer(writer);
    writer.storage_image(kBindingResult, result.view, result.layout);
    const graph::BoundResource& scratch = ctx.resource("half_res");
    writer.sampled_image(kBindingScratch, scratch.view, scratch.layout, nearest);
    if (has_ao_) bind_storage(writer, kBindingAo, "ao");
    const VkExtent3D e = result.info->extent;
    upsample_->bind(cmd);
    writer.push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, upsample_->layout());
    upsample_->push_constants(
        cmd,
        UpsamplePush{e.width, e.height, static_cast<float>(ctx.number("depth_tolerance")), 8.0f});
    vkCmdDispatch(cmd, graph::workgroups(e.width, kTile), graph::workgroups(e.height, kTile), 1);
  }

 private:
  bool specular_ = false;
  bool anisotropic_ = true;
  bool half_ = false;
  bool has_ao_ = false;
  bool has_shadow_ = false;
  bool facing_ = false;
  bool front_light_ = false;  // the facing volumes are bound (contracts::kFacingSlots)
  std::unique_ptr<contracts::VolumeSampler> sampler_;
  std::optional<gpu::ComputePipeline> trace_;
  std::optional<gpu::ComputePipeline> shadow_;
  std::optional<gpu::ComputePipeline> upsample_;
  std::optional<gpu::ComputePipeline> interleave_;
  // Each pixel's own gather before the interleaved average (rgba16f, the traced extent),
  // kept in GENERAL layout.
  std::optional<gpu::Image> gathers_;

  // Makes the image of per-pixel gathers (again, for a new extent) and orders this frame's
  // writes to it after the last frame's reads.
  void prepare_gathers(graph::PassContext& ctx, VkExtent3D extent) {
    VkCommandBuffer cmd = ctx.cmd();
    if (gathers_ && gathers_->extent().width == extent.width &&
        gathers_->extent().height == extent.height) {
      order_gathers(cmd);
      return;
    }
    gpu::ImageDesc desc;
    desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    desc.extent = {extent.width, extent.height, 1};
    desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    desc.name = ctx.pass_name() + ".gathers";
    gathers_.emplace(ctx.gpu(), desc);
    gathers_->transition(cmd, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
  }

  // Compute work on the image of per-pixel gathers after the compute work before it (the
  // average after the trace, and this frame's trace after the last frame's average).
  void order_gathers(VkCommandBuffer cmd) {
    const gpu::BarrierScope compute{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                    VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_SHADER_WRITE_BIT};
    gpu::image_barrier(cmd, gathers_->handle(), gathers_->range(), VK_IMAGE_LAYOUT_GENERAL,
                       VK_IMAGE_LAYOUT_GENERAL, compute, compute);
  }
};

void validate_cone_trace(graph::PassCheck& check) {
  contracts::check_clipmap_info_size(check);
  check_filtered_volumes_bound(check);
  contracts::validate_front_light_slots(check);
  graph::check_same_clipmap_layout(check, "voxel_normal",
                                   {contracts::kFilteredSlot, contracts::kDirectionalSlots[0],
                                    contracts::kFacingSlots[0], contracts::kFacingSlots[1]});
  if (check.choice("resolution") == "half" && !check.has("half_res")) {
    check.param_error("resolution",
                      "'half' needs the output slot 'half_res' bound to an rgba16f image of half "
                      "the viewport");
  }
}

graph::SlotSpec image_output(const char* name, const char* doc, bool optional,
                             std::vector<VkFormat> formats) {
  return {name,
          graph::kinds(graph::ResourceKind::Image2D),
          graph::Access::StorageWrite,
          graph::kStageCompute,
          std::move(formats),
          optional,
          doc};
}

std::vector<graph::SlotSpec> trace_inputs() {
  std::vector<graph::SlotSpec> inputs = {
      contracts::clipmap_info_input(),
      contracts::filtered_volume_input(contracts::kFilteredSlot,
                                       "isotropic filtered volume from vct.filter (or bind the six "
                                       "directional volumes)")};
  const char* directions[] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
  for (size_t i = 0; i < contracts::kDirectionalSlots.size(); ++i) {
    inputs.push_back(contracts::filtered_volume_input(
        contracts::kDirectionalSlots[i], std::string("directional volume for cones travelling ") +
                                             directions[i] + " from vct.filter (anisotropic)"));
  }
  for (const char* slot : contracts::kFacingSlots) inputs.push_back(contracts::facing_input(slot));
  for (contracts::GbufferTarget target :
       {contracts::GbufferTarget::BaseColor, contracts::GbufferTarget::Normal,
        contracts::GbufferTarget::Material, contracts::GbufferTarget::Depth}) {
    inputs.push_back(contracts::gbuffer_input(target));
  }
  inputs.push_back(graph::sampled_clipmap_input(
      "voxel_normal",
      "voxel normals (common.voxelize); with them a cone sees a voxel's light only from the "
      "side its surfaces face",
      true, {VK_FORMAT_R16G16B16A16_SFLOAT}));
  return inputs;
}

std::vector<graph::ParamSpec> trace_params(bool specular) {
  std::vector<graph::ParamSpec> params;
  if (!specular) {
    params.push_back({"diffuse_cones",
                      graph::ParamType::Int,
                      6.0,
                      1.0,
                      32.0,
                      {},
                      "diffuse cones over the hemisphere (equal cosine-weighted cells; weights "
                      "sum to pi)",
                      true});
    params.push_back({"interleave",
                      graph::ParamType::Int,
                      4.0,
                      1.0,
                      4.0,
                      {},
                      "n: the cone set turns about the normal in an n x n pixel pattern and each "
                      "pixel averages the n x n window over its own surface, n^2 turns at the "
                      "cost of one (1: the same cones at every pixel; docs/vct.md)",
                      true});
    params.push_back({"lane_rows",
                      graph::ParamType::Enum,
                      0.0,
                      0.0,
                      0.0,
                      {"aperture", "cell"},
                      "where a cone's two rows of lanes lie: aperture, a quarter of its half "
                      "angle under and over its axis; cell, in the lower and upper half of its "
                      "ring, which samples the hemisphere without bias but is not yet the more "
                      "accurate on closed rooms (docs/vct.md)",
                      true});
    params.push_back({"shadow_cone_angle",
                      graph::ParamType::Float,
                      3.0,
                      0.1,
                      45.0,
                      {},
                      "half angle (degrees) of the soft-shadow cone towards the first light "
                      "(output 'shadow'); wider cones give softer shadows",
                      true});
    params.push_back({"specular_layer",
                      graph::ParamType::Bool,
                      0.0,
                      0.0,
                      1.0,
                      {},
                      "the graph adds vct.cone_trace_specular's light (S L, S the specular "
                      "lobe's directional albedo) on every pixel: the diffuse then reflects "
                      "(1 - S) c_diff, so that the two together never reflect more than "
                      "arrives (set it with the specular pass's condition)",
                      false});
    params.push_back({"ao_falloff",
                      graph::ParamType::Float,
                      0.1,
                      0.0,
                      100.0,
                      {},
                      "lambda of the AO weight 1/(1 + lambda r), r = cone radius in level-0 "
                      "voxels (0: occlusion at any distance counts fully)",
                      true});
  }
  params.push_back(contracts::refine_levels_param(2));
  params.push_back({"lanes",
                    graph::ParamType::Int,
                    8.0,
                    1.0,
                    8.0,
                    {},
                    "lanes of a cone, spread across its width, each reading voxels of its share "
                    "of it and composited on its own (docs/vct.md): an even number from 6 up "
                    "makes two rows, one under and one over the axis's elevation, fewer make one "
                    "row at it; "
                    "1 traces the axis only, several times cheaper on lavapipe, but small bright "
                    "surfaces are hit or missed as blotches",
                    true});
  params.push_back({"step_factor",
                    graph::ParamType::Float,
                    1.0,
                    0.05,
                    4.0,
                    {},
                    "beta: step length / cone diameter; opacity is corrected for the step, so "
                    "smaller values cost more, not change the brightness",
                    true});
  params.push_back(contracts::cone_max_distance_param());
  params.push_back({"normal_offset",
                    graph::ParamType::Float,
                    1.0,
                    0.0,
                    8.0,
                    {},
                    "cone origin offset along the normal, in voxels of the finest level there",
                    true});
  params.push_back({"start_offset",
                    graph::ParamType::Float,
                    1.0,
                    0.0,
                    8.0,
                    {},
                    "distance skipped at the start of each cone, in voxels (self-occlusion)",
                    true});
  params.push_back({"resolution",
                    graph::ParamType::Enum,
                    0.0,
                    0.0,
                    0.0,
                    {"full", "half"},
                    "full: a trace per pixel; half: per 2x2 block into 'half_res', then a depth- "
                    "and normal-aware upsample",
                    false});
  params.push_back({"depth_tolerance",
                    graph::ParamType::Float,
                    0.05,
                    0.001,
                    1.0,
                    {},
                    "half resolution: relative view-depth difference at which an upsampling tap "
                    "weighs one half",
                    true});
  return params;
}

}  // namespace

void register_cone_trace(graph::Registry& registry) {
  graph::PassTypeInfo info;
  info.type = "vct.cone_trace";
  info.doc =
      "Indirect diffuse (c_diff/pi x cone-traced irradiance) and ambient occlusion by diffuse "
      "cones through the filtered voxel volumes";
  info.inputs = trace_inputs();
  info.outputs = {
      image_output("diffuse", "indirect diffuse outgoing radiance", false,
                   {VK_FORMAT_R16G16B16A16_SFLOAT}),
      image_output("ao", "ambient-occlusion visibility (1 = open)", true,
                   {VK_FORMAT_R8_UNORM, VK_FORMAT_R16_SFLOAT, VK_FORMAT_R8G8B8A8_UNORM,
                    VK_FORMAT_R16G16B16A16_SFLOAT}),
      image_output("half_res", "scratch for resolution 'half' (rgba16f, viewport/2)", true,
                   {VK_FORMAT_R16G16B16A16_SFLOAT}),
      image_output("shadow",
                   "soft-shadow cone visibility of the scene's first light (1 = lit), full "
                   "resolution; unbound: not traced",
                   true,
                   {VK_FORMAT_R8_UNORM, VK_FORMAT_R16_SFLOAT, VK_FORMAT_R8G8B8A8_UNORM,
                    VK_FORMAT_R16G16B16A16_SFLOAT})};
  info.params = trace_params(false);
  info.validate = validate_cone_trace;
  registry.add(std::move(info), [] { return std::make_unique<ConeTracePass>(false); });
}

void register_cone_trace_specular(graph::Registry& registry) {
  graph::PassTypeInfo info;
  info.type = "vct.cone_trace_specular";
  info.doc =
      "Indirect specular: one cone along the reflection, aperture from GGX roughness, times "
      "the lobe's directional albedo";
  info.inputs = trace_inputs();
  info.outputs = {image_output("specular", "indirect specular outgoing radiance", false,
                               {VK_FORMAT_R16G16B16A16_SFLOAT}),
                  image_output("half_res", "scratch for resolution 'half' (rgba16f, viewport/2)",
                               true, {VK_FORMAT_R16G16B16A16_SFLOAT})};
  info.params = trace_params(true);
  info.validate = validate_cone_trace;
  registry.add(std::move(info), [] { return std::make_unique<ConeTracePass>(true); });
}

}  // namespace voxgi::passes::vct
