// Shadow maps for every shadowed light: an orthographic map fitted to the scene bounds for
// directional lights, a perspective map covering the cone for spot lights and six cube faces
// for point lights, all layers of one depth array image. Re-renders only when lights or
// geometry changed.

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/graph/pass.hpp"
#include "engine/scene/gpu_scene.hpp"
#include "engine/scene/scene.hpp"
#include "passes/common/passes.hpp"
#include "passes/common/shader_helpers.hpp"
#include "passes/contracts/shadow_data.hpp"

namespace voxgi::passes::common {
namespace {

using contracts::kShadowFacesPerLight;
using contracts::ShadowLight;
using graph::Access;
using graph::ResourceKind;

glm::vec3 up_for(const glm::vec3& direction) {
  return std::abs(direction.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
}

// Near and far planes for a perspective shadow from `position` that covers the whole scene.
void perspective_range(const scene::BoundingSphere& sphere, const glm::vec3& position, float& znear,
                       float& zfar) {
  zfar = glm::length(sphere.center - position) + sphere.radius;
  zfar = std::max(zfar, 1e-3f) * 1.01f;
  znear = std::max(zfar * 1e-4f, 1e-5f);
}

ShadowLight shadow_for(const scene::Light& light, const scene::BoundingSphere& sphere,
                       float resolution) {
  ShadowLight shadow{};
  const glm::vec3 dir = glm::normalize(light.direction);
  if (light.type == scene::LightType::Directional) {
    const float r = sphere.radius;
    const glm::vec3 eye = sphere.center - dir * (2.0f * r);
    const glm::mat4 view = glm::lookAt(glm::vec3(0.0f), dir, up_for(dir));
    const glm::mat4 proj = glm::ortho(-r, r, -r, r, r * 0.5f, r * 3.5f);
    shadow.view_proj[0] = proj * view;
    shadow.origin = glm::vec4(eye, 1.0f);
    shadow.info = {1.0f, 2.0f * r / resolution, 0.0f, 0.0f};
    return shadow;
  }
  float znear = 0.0f, zfar = 0.0f;
  perspective_range(sphere, light.position, znear, zfar);
  shadow.origin = glm::vec4(light.position, 1.0f);
  if (light.type == scene::LightType::Spot) {
    const float fov = std::min(2.0f * light.outer_cone + 0.05f, glm::radians(170.0f));
    const glm::mat4 view = glm::lookAt(glm::vec3(0.0f), dir, up_for(dir));
    shadow.view_proj[0] = glm::perspective(fov, 1.0f, znear, zfar) * view;
    shadow.info = {1.0f, 2.0f * std::tan(0.5f * fov) / resolution, 1.0f, 0.0f};
    return shadow;
  }
  // Point light: cube faces +X, -X, +Y, -Y, +Z, -Z; the lighting shader picks the face by the
  // major axis of the light-to-point direction, so each face only has to cover its 90° frustum.
  static const glm::vec3 kFaceDirs[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                         {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  static const glm::vec3 kFaceUps[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1},
                                        {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  // A hair over 90° so that PCF taps at face edges stay inside the face.
  const float fov = glm::radians(92.0f);
  const glm::mat4 proj = glm::perspective(fov, 1.0f, znear, zfar);
  for (int face = 0; face < 6; ++face) {
    shadow.view_proj[face] = proj * glm::lookAt(glm::vec3(0.0f), kFaceDirs[face], kFaceUps[face]);
  }
  shadow.info = {6.0f, 2.0f * std::tan(0.5f * fov) / resolution, 1.0f, 0.0f};
  return shadow;
}

struct ShadowPush {
  glm::mat4 view_proj;  // relative to origin
  glm::vec4 origin;
};

class ShadowMapsPass final : public graph::Pass {
 public:
  void setup(graph::PassContext& ctx) override {
    gpu::GraphicsPipelineDesc desc;
    desc.name = ctx.pass_name();
    desc.vertex = graph::compile_pass_shader(ctx, "common/shadow.vert");
    desc.layout.extra_set_layouts = {ctx.gpu_scene().set_layout()};
    desc.layout.push_constant_size = sizeof(ShadowPush);
    desc.layout.push_constant_stages = VK_SHADER_STAGE_VERTEX_BIT;
    desc.vertex_bindings = {scene::GpuScene::vertex_binding()};
    for (const VkVertexInputAttributeDescription& a : scene::GpuScene::vertex_attributes()) {
      if (a.location == 0) desc.vertex_attributes.push_back(a);
    }
    desc.depth_test = true;
    desc.depth_write = true;
    desc.depth_compare = VK_COMPARE_OP_LESS;
    desc.depth_bias = true;
    desc.depth_clamp = true;  // occluders behind the near plane of an orthographic map still cast
    desc.cull = VK_CULL_MODE_NONE;
    desc.depth_format = ctx.info("maps").format;
    pipeline_.emplace(ctx.gpu(), desc);
  }

  std::string skip_reason(const graph::PassContext& ctx) const override {
    const graph::FrameInfo& frame = ctx.frame();
    if (frame.first_frame || frame.lights_changed || frame.geometry_changed ||
        ctx.params_changed()) {
      return {};
    }
    return "lights and geometry unchanged";
  }

  void execute(graph::PassContext& ctx) override {
    const graph::ResourceInfo& maps = ctx.info("maps");
    const uint32_t light_slots = std::min<uint32_t>(
        maps.array_layers / kShadowFacesPerLight, static_cast<uint32_t>(ctx.integer("max_lights")));
    const graph::ResourceInfo& matrices_info = ctx.info("matrices");
    const uint32_t buffer_slots =
        static_cast<uint32_t>(matrices_info.buffer_size / sizeof(ShadowLight));
    const uint32_t slots = std::min(light_slots, buffer_slots);

    const scene::Scene& scene = ctx.scene();
    // The bounds walk every vertex: redo it only when geometry moved, not when only lights did.
    if (!sphere_ || ctx.frame().first_frame || ctx.frame().geometry_changed) {
      sphere_ = scene.bounding_sphere();
    }
    const scene::BoundingSphere sphere = *sphere_;
    const float resolution = static_cast<float>(maps.extent.width);
    std::vector<ShadowLight> shadows(std::max<uint32_t>(slots, 1));
    for (uint32_t i = 0; i < slots && i < scene.lights.size(); ++i) {
      shadows[i] = shadow_for(scene.lights[i], sphere, resolution);
    }
    VkCommandBuffer cmd = ctx.cmd();
    gpu::Buffer& matrices = *ctx.resource("matrices").buffer;
    const VkDeviceSize bytes =
        std::min<VkDeviceSize>(shadows.size() * sizeof(ShadowLight), matrices.size());
    vkCmdUpdateBuffer(cmd, matrices.handle(), 0, bytes, shadows.data());

    const scene::GpuScene& gpu_scene = ctx.gpu_scene();
    gpu::Image& image = *ctx.resource("maps").image;
    const VkImageLayout layout = ctx.resource("maps").layout;
    for (uint32_t light = 0; light < slots; ++light) {
      const uint32_t faces = static_cast<uint32_t>(shadows[light].info.x);
      for (uint32_t face = 0; face < faces; ++face) {
        render_layer(ctx, gpu_scene, image.layer_view(light * kShadowFacesPerLight + face), layout,
                     maps.extent,
                     ShadowPush{shadows[light].view_proj[face], shadows[light].origin});
      }
    }
  }

 private:
  void render_layer(graph::PassContext& ctx, const scene::GpuScene& scene, VkImageView view,
                    VkImageLayout layout, VkExtent3D extent, const ShadowPush& push) {
    VkCommandBuffer cmd = ctx.cmd();
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = view;
    depth.imageLayout = layout;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth.clearValue.depthStencil = {1.0f, 0};
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, {extent.width, extent.height}};
    rendering.layerCount = 1;
    rendering.pDepthAttachment = &depth;
    vkCmdBeginRendering(cmd, &rendering);
    if (!scene.draws().empty()) {
      pipeline_->bind(cmd);
      vkCmdSetDepthBias(cmd, static_cast<float>(ctx.number("depth_bias")), 0.0f,
                        static_cast<float>(ctx.number("slope_bias")));
      gpu::GraphicsPipeline::set_viewport(cmd, extent.width, extent.height);
      VkDescriptorSet scene_set = scene.descriptor_set();
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_->layout(), 1, 1,
                              &scene_set, 0, nullptr);
      pipeline_->push_constants(cmd, push);
      scene.record_draws(cmd);
    }
    vkCmdEndRendering(cmd);
  }

  std::optional<gpu::GraphicsPipeline> pipeline_;
  std::optional<scene::BoundingSphere> sphere_;
};

}  // namespace

void register_shadow_maps(graph::Registry& registry) {
  graph::PassTypeInfo info;
  info.type = "common.shadow_maps";
  info.doc =
      "Depth maps of the scene from each light (directional: fitted orthographic, spot: "
      "perspective, point: six cube faces), six array layers per light";
  info.outputs = {
      {"maps",
       graph::kinds(ResourceKind::Image2D),
       Access::DepthAttachment,
       graph::kStageFragment,
       {contracts::kShadowMapFormat},
       false,
       "depth array, 6 layers per shadowed light"},
      {"matrices",
       graph::kinds(ResourceKind::Buffer),
       Access::TransferWrite,
       graph::kStageTransfer,
       {},
       false,
       "per light: 6 view-projection matrices and info (shadow_data.glsl)"},
  };
  info.params = {
      {"max_lights",
       graph::ParamType::Int,
       64.0,
       0.0,
       64.0,
       {},
       "lights (in scene order) that get shadow maps; the image's layers / 6 limit it too",
       false,
       true},
      {"resolution",
       graph::ParamType::Int,
       1024.0,
       16.0,
       16384.0,
       {},
       "edge of each shadow map face in texels, for maps the graph declares without a size",
       false,
       true},
      {"depth_bias",
       graph::ParamType::Float,
       2.0,
       0.0,
       1000.0,
       {},
       "constant depth bias in depth-buffer units",
       true},
      {"slope_bias", graph::ParamType::Float, 2.0, 0.0, 100.0, {}, "slope-scaled depth bias", true},
  };
  // Six layers and one ShadowLight record per shadowed light present (at least one, so a
  // scene without lights still binds valid resources).
  const auto shadowed_lights = [](const graph::SizeQuery& query) {
    const double present =
        std::min(query.scene_value("scene.light_count"), query.number("max_lights"));
    return static_cast<uint32_t>(std::max(1.0, present));
  };
  graph::set_size_rule(info, "maps", [shadowed_lights](const graph::SizeQuery& query) {
    graph::DerivedSize size;
    size.width = size.height = static_cast<uint32_t>(query.number("resolution"));
    size.layers = contracts::kShadowFacesPerLight * shadowed_lights(query);
    return size;
  });
  graph::set_size_rule(info, "matrices", [shadowed_lights](const graph::SizeQuery& query) {
    graph::DerivedSize size;
    size.bytes = contracts::kShadowLightBytes * shadowed_lights(query);
    return size;
  });
  info.may_skip = true;
  registry.add(std::move(info), [] { return std::make_unique<ShadowMapsPass>(); });
}

}  // namespace voxgi::passes::common
