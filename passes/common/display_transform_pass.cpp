// Display transform: scene-referred linear radiance to display-referred sRGB through the
// shipped OpenColorIO config. OCIO's processor is baked once per view into a 3D LUT with a log2
// shaper (engine/color); the shader applies exposure, the shaper and a trilinear lookup.

#include <glm/gtc/packing.hpp>

#include <memory>
#include <optional>
#include <vector>

#include "engine/color/display_transform.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/graph/pass.hpp"
#include "passes/common/passes.hpp"
#include "passes/common/shader_helpers.hpp"

namespace voxgi::passes::common {
namespace {

using graph::Access;
using graph::ResourceKind;

constexpr const char* kDisplay = "sRGB";
constexpr uint32_t kLutSize = 65;

struct DisplayPush {
  uint32_t width;
  uint32_t height;
  float exposure_scale;  // 2^EV
  float shaper_min_log2;
  float shaper_max_log2;
  float pad[3];
};

class DisplayTransformPass final : public graph::Pass {
 public:
  void setup(graph::PassContext& ctx) override {
    if (!transform_) transform_ = std::make_unique<color::DisplayTransform>();
    const std::string& view = ctx.choice("view");
    const color::DisplayTransform::Lut lut = transform_->bake(kDisplay, view, kLutSize);
    shaper_min_log2_ = lut.shaper_min_log2;
    shaper_max_log2_ = lut.shaper_max_log2;

    // float16 texels: linear filtering of 3D RGBA16F images is universally supported, and the
    // LUT's outputs are display values in 0..1 where half precision is far below 8-bit steps.
    std::vector<uint16_t> texels(lut.rgba.size());
    for (size_t i = 0; i < texels.size(); ++i) texels[i] = glm::packHalf1x16(lut.rgba[i]);
    gpu::ImageDesc desc;
    desc.type = VK_IMAGE_TYPE_3D;
    desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    desc.extent = {lut.size, lut.size, lut.size};
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    desc.name = ctx.pass_name() + ".lut";
    lut_image_.emplace(ctx.gpu(), desc);
    lut_image_->upload(texels.data(), texels.size() * sizeof(uint16_t),
                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);

    pipeline_.emplace(graph::make_pass_compute(ctx, "common/display_transform.comp",
                                               {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
                                                {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
                                                {2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 0}},
                                               sizeof(DisplayPush), false));
  }

  void execute(graph::PassContext& ctx) override {
    VkCommandBuffer cmd = ctx.cmd();
    const graph::BoundResource& in = ctx.resource("radiance");
    const graph::BoundResource& out = ctx.resource("display");
    const VkExtent3D extent = out.info->extent;
    pipeline_->bind(cmd);
    gpu::DescriptorWriter()
        .sampled_image(0, in.view, in.layout, ctx.gpu().sampler(gpu::SamplerKind::NearestClamp))
        .sampled_image(1, lut_image_->view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                       ctx.gpu().sampler(gpu::SamplerKind::LinearClamp))
        .storage_image(2, out.view, out.layout)
        .push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout());
    DisplayPush push{};
    push.width = extent.width;
    push.height = extent.height;
    push.exposure_scale = static_cast<float>(std::exp2(ctx.number("exposure")));
    push.shaper_min_log2 = shaper_min_log2_;
    push.shaper_max_log2 = shaper_max_log2_;
    pipeline_->push_constants(cmd, push);
    dispatch_over_image(cmd, extent.width, extent.height);
  }

 private:
  std::unique_ptr<color::DisplayTransform> transform_;
  std::optional<gpu::Image> lut_image_;
  std::optional<gpu::ComputePipeline> pipeline_;
  float shaper_min_log2_ = 0.0f;
  float shaper_max_log2_ = 1.0f;
};

}  // namespace

void register_display_transform(graph::Registry& registry) {
  graph::PassTypeInfo info;
  info.type = "common.display_transform";
  info.doc = "OpenColorIO display transform (sRGB display) baked to a 3D LUT";
  info.inputs = {{"radiance",
                  graph::kinds(ResourceKind::Image2D),
                  Access::Sampled,
                  graph::kStageCompute,
                  {},
                  false,
                  "scene-referred linear radiance"}};
  info.outputs = {{"display",
                   graph::kinds(ResourceKind::Image2D),
                   Access::StorageWrite,
                   graph::kStageCompute,
                   {VK_FORMAT_R8G8B8A8_UNORM},
                   false,
                   "display-referred sRGB-encoded colour, ready for an 8-bit file"}};
  info.params = {
      {"view",
       graph::ParamType::Enum,
       0.0,
       0.0,
       2.0,
       {"Standard", "ACES 1.0 SDR-video", "Raw"},
       "OCIO view of the sRGB display (third_party_config/ocio/config.ocio)",
       false},
      {"exposure",
       graph::ParamType::Float,
       0.0,
       -20.0,
       20.0,
       {},
       "exposure in stops applied before the view transform",
       true},
  };
  registry.add(std::move(info), [] { return std::make_unique<DisplayTransformPass>(); });
}

}  // namespace voxgi::passes::common
