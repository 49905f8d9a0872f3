// common.voxelize: rasterizes the scene into clipmap volumes of albedo, normal and emission
// (docs/voxelization.md). Each frame it works out which boxes of voxels are stale (a whole
// level at first, the slabs a moving window exposes, the old and new places of moving
// objects), and for each box: accumulates every object touching it into the scratch buffer
// (one draw per object, dominant-axis projection, conservative coverage, atomics), then
// resolves the sums into the volumes. Static voxels are never cleared except where a box
// recomputes them, and the fixed-point sums make that recomputation bit-identical.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/graph/pass.hpp"
#include "engine/scene/gpu_scene.hpp"
#include "engine/scene/scene.hpp"
#include "passes/common/passes.hpp"
#include "passes/common/shader_helpers.hpp"
#include "passes/common/voxel_clipmap_window.hpp"
#include "passes/contracts/voxel_clipmap.hpp"
#include "passes/contracts/voxel_volumes.hpp"

namespace voxgi::passes::common {
namespace {

using graph::Access;
using graph::ResourceKind;

// Mirrors VoxelDrawPush in shaders/common/voxel_draw.glsl.
struct VoxelDrawPush {
  glm::vec4 anchor;
  glm::vec4 level_min_size;
  glm::ivec4 box_min;  // w: viewport edge
  glm::ivec4 box_max;  // w: scratch words per voxel
  glm::ivec4 origin;   // xyz: the window's min corner in voxels from the anchor
};
struct VoxelResolvePush {
  glm::ivec4 box_min;  // w: level
  glm::ivec4 box_max;  // w: R
  glm::ivec4 origin;   // w: scratch words per voxel
};
struct VoxelClearPush {
  uint32_t words;
};

constexpr uint32_t kHdrWords = 9;
constexpr uint32_t kHdrWordsWithEmission = 16;
constexpr uint32_t kRgba8Words = 3;
constexpr uint32_t kFrontWords = 6;  // stacked_surfaces = front: one word per facing
constexpr uint32_t kFaceWords = 30;  // a faces output: area, normal sum, front plane per facing
// Voxels of a level kept between its window and the next coarser one's edge (two coarser
// voxels: a trilinear footprint there stays inside that window; nest_window_origins).
constexpr int kNestingMargin = 4;

bool is_power_of_two(uint32_t v) {
  return v != 0 && (v & (v - 1)) == 0;
}

// Whether the node or one of its ancestors is animated (its instances may move).
bool node_may_move(const scene::Scene& scene, int node) {
  for (int n = node; n >= 0 && n < static_cast<int>(scene.nodes.size());
       n = scene.nodes[size_t(n)].parent) {
    if (scene.nodes[size_t(n)].animated) return true;
  }
  return false;
}

// 32-bit words of the scratch record of one voxel.
template <typename Declaration>
uint32_t scratch_words_per_voxel(const Declaration& pass) {
  const uint32_t front = pass.choice("stacked_surfaces") == "front" ? kFrontWords : 0;
  if (pass.choice("strategy") == "average_rgba8") return kRgba8Words + front;
  const uint32_t faces = pass.has("faces") ? kFaceWords : 0;
  return (pass.has("emission") ? kHdrWordsWithEmission : kHdrWords) + faces + front;
}

// The clipmaps' size from parameters "resolution" and "levels", for a graph that leaves the
// volumes' size to this pass; 0 in either means the graph sizes them.
graph::DerivedSize clipmap_size(const graph::SizeQuery& query) {
  graph::DerivedSize size;
  size.resolution = static_cast<uint32_t>(query.number("resolution"));
  size.levels = static_cast<uint32_t>(query.number("levels"));
  if (size.resolution == 0 || size.levels == 0) {
    size.unavailable = "its parameters 'resolution' and 'levels' are not set";
  }
  return size;
}

// R^3 accumulation records: a whole level voxelizes in one go.
graph::DerivedSize scratch_size(const graph::SizeQuery& query) {
  graph::DerivedSize size = clipmap_size(query);
  if (!size.unavailable.empty()) return size;
  const uint32_t words = scratch_words_per_voxel(query);
  size.bytes = VkDeviceSize(size.resolution) * size.resolution * size.resolution * words * 4;
  return size;
}

// What the device cannot change: clipmap shape, matching volumes, buffer sizes.
void validate_voxelize(graph::PassCheck& check) {
  const graph::ResourceInfo& albedo = check.info("albedo");
  const uint32_t resolution = albedo.extent.width;
  const uint32_t levels = albedo.clipmap_levels;
  const int wanted_resolution = check.integer("resolution");
  const int wanted_levels = check.integer("levels");
  if ((wanted_resolution != 0 && uint32_t(wanted_resolution) != resolution) ||
      (wanted_levels != 0 && uint32_t(wanted_levels) != levels)) {
    check.slot_error("albedo",
                     "clipmap '" + albedo.name + "' is declared with " + std::to_string(levels) +
                         " levels of " + std::to_string(resolution) +
                         "^3, but the pass's parameters ask for " + std::to_string(wanted_levels) +
                         " of " + std::to_string(wanted_resolution) +
                         "^3: leave the clipmaps' size to the pass (no 'resolution' or "
                         "'levels' in the graph) or set the parameters to 0");
  }
  if (levels < 1 || levels > contracts::kVoxelMaxLevels) {
    check.slot_error("albedo", "clipmap '" + albedo.name + "' has " + std::to_string(levels) +
                                   " levels; 1 to " + std::to_string(contracts::kVoxelMaxLevels) +
                                   " are supported");
  }
  if (!is_power_of_two(resolution) || resolution < 8) {
    check.slot_error("albedo", "clipmap '" + albedo.name + "' has resolution " +
                                   std::to_string(resolution) +
                                   "; the clipmap needs a power of two of at least 8");
  }
  graph::check_same_clipmap_layout(check, "albedo", {"normal", "emission", "faces"});
  contracts::check_clipmap_info_size(check);
  const uint32_t stride = scratch_words_per_voxel(check);
  const graph::ResourceInfo& scratch = check.info("scratch");
  const VkDeviceSize row_bytes = VkDeviceSize(resolution) * stride * 4;
  if (scratch.buffer_size < row_bytes) {
    check.slot_error("scratch", "buffer '" + scratch.name + "' holds " +
                                    std::to_string(scratch.buffer_size) + " bytes; at least " +
                                    std::to_string(row_bytes) + " (one row of R voxels x " +
                                    std::to_string(stride * 4) + " bytes) is needed, R^3 x that (" +
                                    std::to_string(row_bytes * resolution * resolution) +
                                    ") voxelizes a level at once");
  }
}

bool intersects(const VoxelBox& a, const VoxelBox& b) {
  return !a.empty() && !b.empty() && glm::all(glm::lessThan(a.min, b.max)) &&
         glm::all(glm::lessThan(b.min, a.max));
}

class VoxelizePass final : public graph::Pass {
 public:
  void setup(graph::PassContext& ctx) override {
    const graph::ResourceInfo& albedo = ctx.info("albedo");
    resolution_ = albedo.extent.width;
    levels_ = albedo.clipmap_levels;
    const std::string where = "pass '" + ctx.pass_name() + "' (common.voxelize): ";
    has_emission_ = ctx.has("emission");
    has_faces_ = ctx.has("faces");
    rgba8_ = ctx.choice("strategy") == "average_rgba8";
    stride_ = scratch_words_per_voxel(ctx);
    capacity_voxels_ =
        static_cast<int64_t>(ctx.info("scratch").buffer_size / (VkDeviceSize(stride_) * 4));

    if (!ctx.gpu().features().geometry_shader) {
      throw std::runtime_error(where +
                               "the device has no geometry shaders, which voxelization "
                               "needs for the dominant-axis projection");
    }
    const std::string& mode = ctx.choice("conservative");
    bool hardware =
        mode == "hardware" || (mode == "auto" && ctx.gpu().features().conservative_rasterization);
    if (mode == "hardware" && !ctx.gpu().features().conservative_rasterization) {
      throw std::runtime_error(where +
                               "parameter 'conservative': 'hardware' needs "
                               "VK_EXT_conservative_rasterization, which this device "
                               "lacks; use 'auto' or 'geometry_shader'");
    }
    const int conservative = mode == "off" ? 0 : (hardware ? 2 : 1);

    std::vector<gpu::ShaderDefine> defines = {{"VOXEL_CONSERVATIVE", std::to_string(conservative)}};
    if (rgba8_) defines.push_back({"VOXEL_STRATEGY_RGBA8", "1"});
    if (has_emission_) defines.push_back({"VOXEL_HAS_EMISSION", "1"});
    if (has_faces_) defines.push_back({"VOXEL_FACES", "1"});

    gpu::GraphicsPipelineDesc desc;
    desc.name = ctx.pass_name();
    desc.vertex = graph::compile_pass_shader(ctx, "common/voxelize.vert", defines);
    desc.geometry = graph::compile_pass_shader(ctx, "common/voxelize.geom", defines);
    std::vector<gpu::ShaderDefine> accumulate_defines = defines;
    const bool stacked_front = ctx.choice("stacked_surfaces") == "front";
    if (stacked_front) accumulate_defines.push_back({"VOXEL_FRONT", "2"});
    desc.fragment = graph::compile_pass_shader(ctx, "common/voxelize.frag", accumulate_defines);
    desc.layout.bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_FRAGMENT_BIT}};
    desc.layout.extra_set_layouts = {ctx.gpu_scene().set_layout()};
    desc.layout.push_constant_size = sizeof(VoxelDrawPush);
    desc.layout.push_constant_stages =
        VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_GEOMETRY_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    desc.vertex_bindings = {scene::GpuScene::vertex_binding()};
    for (const VkVertexInputAttributeDescription& a : scene::GpuScene::vertex_attributes()) {
      if (a.location != 2) desc.vertex_attributes.push_back(a);  // no tangents
    }
    desc.cull = VK_CULL_MODE_NONE;
    desc.conservative_rasterization = conservative == 2;
    draw_pipeline_.emplace(ctx.gpu(), desc);
    front_pipeline_.reset();
    if (stacked_front) {
      std::vector<gpu::ShaderDefine> front_defines = defines;
      front_defines.push_back({"VOXEL_FRONT", "1"});
      desc.name = ctx.pass_name() + " (front surfaces)";
      desc.fragment = graph::compile_pass_shader(ctx, "common/voxelize.frag", front_defines);
      front_pipeline_.emplace(ctx.gpu(), desc);
    }

    std::vector<gpu::Binding> resolve_bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                                  {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                                                  {2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
    if (has_emission_) resolve_bindings.push_back({3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE});
    if (has_faces_) resolve_bindings.push_back({4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE});
    resolve_pipeline_.emplace(graph::make_pass_compute(ctx, "common/voxel_resolve.comp",
                                                       resolve_bindings, sizeof(VoxelResolvePush),
                                                       false, defines));
    clear_pipeline_.emplace(graph::make_pass_compute(ctx, "common/voxel_clear.comp",
                                                     {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}},
                                                     sizeof(VoxelClearPush), false));
    initialized_ = false;
    scratch_clean_ = false;
  }

  std::string skip_reason(const graph::PassContext& ctx) const override {
    if (!initialized_ || ctx.params_changed()) return {};
    const std::vector<glm::ivec3> origins = target_origins(ctx);
    for (uint32_t l = 0; l < levels_; ++l) {
      if (origins[l] != origins_[l]) return {};
    }
    if (needs_reanchor(ctx)) return {};
    if (ctx.frame().geometry_changed || ctx.frame().first_frame) {
      const std::vector<scene::Instance> instances = ctx.scene().instances();
      for (const DynamicInstance& d : dynamic_) {
        if (d.index >= instances.size() || instances[d.index].world != d.world) return {};
      }
    }
    return "static voxels up to date, window unchanged";
  }

  void execute(graph::PassContext& ctx) override {
    const scene::Scene& scene = ctx.scene();
    const std::vector<scene::Instance> instances = scene.instances();
    if (!initialized_ || needs_reanchor(ctx)) initialize(ctx, instances);

    // Current bounds of every instance (static ones never move; dynamic ones are re-read).
    std::vector<WorldBox> boxes(instances.size());
    for (size_t i = 0; i < instances.size(); ++i) {
      const scene::Instance& inst = instances[i];
      const scene::Primitive& prim =
          scene.meshes[size_t(inst.mesh)].primitives[size_t(inst.primitive)];
      boxes[i] = transform_box(prim.bounds_min, prim.bounds_max, inst.world);
    }

    const std::vector<glm::ivec3> origins = target_origins(ctx);
    std::vector<VoxelBox> stale;
    std::vector<bool> full(levels_, false);
    bool windows_moved = !info_written_;
    for (uint32_t l = 0; l < levels_; ++l) {
      const int level = static_cast<int>(l);
      if (!valid_[l]) {
        full[l] = true;
        stale.push_back({level, glm::ivec3(0), glm::ivec3(static_cast<int>(resolution_))});
      } else if (origins[l] != origins_[l]) {
        for (const VoxelBox& b : exposed_slabs(level, origins_[l], origins[l], resolution_)) {
          stale.push_back(b);
        }
      }
      if (origins[l] != origins_[l]) windows_moved = true;
    }
    // Moving objects: where they were (to clear them) and where they are now.
    for (DynamicInstance& d : dynamic_) {
      if (d.index >= instances.size()) continue;
      const bool moved = !d.voxelized || instances[d.index].world != d.world;
      if (!moved) continue;
      for (uint32_t l = 0; l < levels_; ++l) {
        if (full[l]) continue;
        const double size = level_size(l);
        if (d.voxelized) {
          stale.push_back(
              window_box(static_cast<int>(l), d.box, anchor_, origins[l], size, resolution_, 1));
        }
        stale.push_back(window_box(static_cast<int>(l), boxes[d.index], anchor_, origins[l], size,
                                   resolution_, 1));
      }
      d.world = instances[d.index].world;
      d.box = boxes[d.index];
      d.voxelized = true;
    }
    stale = merge_overlapping(std::move(stale));

    if (windows_moved) write_info(ctx, origins);

    std::vector<VoxelBox> chunks;
    for (const VoxelBox& b : stale) {
      for (const VoxelBox& c : split_box(b, capacity_voxels_)) chunks.push_back(c);
    }
    if (!chunks.empty()) {
      int64_t most = 0;
      for (const VoxelBox& c : chunks) most = std::max(most, c.voxels());
      // Every resolve leaves the records it read zeroed, so a persistent scratch stays clean
      // between frames; a transient one may share memory with other resources.
      if (!ctx.info("scratch").persistent || !scratch_clean_) {
        clear_scratch(ctx, static_cast<uint32_t>(most * stride_), most >= capacity_voxels_);
      }
      for (size_t i = 0; i < chunks.size(); ++i) {
        voxelize_chunk(ctx, chunks[i], origins[size_t(chunks[i].level)], boxes);
        if (i + 1 < chunks.size()) {
          // The next chunk may overlap this one's voxels and reuses the scratch.
          ctx.barrier_within_pass("albedo");
          ctx.barrier_within_pass("normal");
          if (has_emission_) ctx.barrier_within_pass("emission");
          if (has_faces_) ctx.barrier_within_pass("faces");
        }
      }
    }
    origins_ = origins;
    std::fill(valid_.begin(), valid_.end(), true);
  }

 private:
  struct DynamicInstance {
    size_t index = 0;
    glm::mat4 world{1.0f};
    WorldBox box;
    bool voxelized = false;
  };

  double level_size(uint32_t level) const { return voxel_size_ * std::ldexp(1.0, int(level)); }

  bool follows_camera(const graph::PassContext& ctx) const {
    const std::string& center = ctx.choice("center");
    if (center == "camera") return true;
    if (center == "scene") return false;
    return levels_ > 1;
  }

  glm::dvec3 window_center(const graph::PassContext& ctx) const {
    if (!follows_camera(ctx)) return scene_center_;
    const glm::vec4 camera = ctx.frame().uniforms.camera_position;
    const bool finite =
        std::isfinite(camera.x) && std::isfinite(camera.y) && std::isfinite(camera.z);
    if (!finite) return scene_center_;
    return window_center_in_scene(glm::dvec3(camera.x, camera.y, camera.z), scene_min_, scene_max_);
  }

  // Far from the anchor the integer voxel origins would overflow: start over around the camera.
  bool needs_reanchor(const graph::PassContext& ctx) const {
    if (!initialized_) return true;
    const glm::dvec3 d = glm::abs(window_center(ctx) - anchor_) / voxel_size_;
    return !(std::max({d.x, d.y, d.z}) < double(1 << 26));
  }

  std::vector<glm::ivec3> target_origins(const graph::PassContext& ctx) const {
    std::vector<glm::ivec3> out(levels_);
    const glm::dvec3 center = window_center(ctx);
    for (uint32_t l = 0; l < levels_; ++l) {
      // A window centred on the scene (center = scene, one level) comes back where it was.
      const double half_width = 0.5 * static_cast<double>(resolution_) * level_size(l);
      glm::dvec3 rel = level_window_center(center, scene_min_, scene_max_, half_width) - anchor_;
      if (!glm::all(glm::lessThan(glm::abs(rel), glm::dvec3(1e300)))) rel = glm::dvec3(0.0);
      out[l] = window_origin(rel, level_size(l), resolution_);
    }
    nest_window_origins(out, resolution_, kNestingMargin);
    return out;
  }

  void initialize(graph::PassContext& ctx, const std::vector<scene::Instance>& instances) {
    const scene::Scene& scene = ctx.scene();
    glm::vec3 mn, mx;
    scene.bounds(mn, mx);
    scene_min_ = glm::dvec3(mn);
    scene_max_ = glm::dvec3(mx);
    scene_center_ = 0.5 * (scene_min_ + scene_max_);
    const glm::dvec3 side = glm::dvec3(mx) - glm::dvec3(mn);
    const double extent = std::max({side.x, side.y, side.z});
    if (!initialized_) {  // re-anchoring far away keeps the voxel size
      voxel_size_ = ctx.number("voxel_size");
      if (!(voxel_size_ > 0.0)) {
        // Windows that follow the camera must reach from it to the far side of the scene,
        // or a camera outside the scene leaves the back of the scene out of every level.
        const double reach = follows_camera(ctx)
                                 ? window_reach(window_center(ctx), glm::dvec3(mn), glm::dvec3(mx))
                                 : 0.0;
        voxel_size_ = auto_voxel_size(extent, resolution_, levels_, reach);
      }
    }
    const double coarsest = level_size(levels_ - 1);
    glm::dvec3 around = scene_center_;
    if (initialized_) around = window_center(ctx);  // re-anchoring far away
    anchor_f_ = glm::vec3(follows_camera(ctx) ? snap_anchor(around, coarsest)
                                              : fixed_window_anchor(around, coarsest, resolution_));
    anchor_ = glm::dvec3(anchor_f_);
    initialized_ = true;
    origins_.assign(levels_, glm::ivec3(0));
    valid_.assign(levels_, false);
    info_written_ = false;
    dynamic_.clear();
    for (size_t i = 0; i < instances.size(); ++i) {
      if (node_may_move(scene, instances[i].node)) dynamic_.push_back({i, {}, {}, false});
    }
  }

  void write_info(graph::PassContext& ctx, const std::vector<glm::ivec3>& origins) {
    contracts::VoxelClipmapInfo info{};
    info.anchor = glm::vec4(anchor_f_, 0.0f);
    info.dims = glm::uvec4(resolution_, levels_, 0, 0);
    for (uint32_t l = 0; l < levels_; ++l) {
      const double size = level_size(l);
      info.levels[l].origin_voxel = glm::ivec4(origins[l], 1);
      info.levels[l].min_corner_size =
          glm::vec4(glm::vec3(glm::dvec3(origins[l]) * size), static_cast<float>(size));
    }
    vkCmdUpdateBuffer(ctx.cmd(), ctx.resource("clipmap_info").buffer->handle(), 0, sizeof(info),
                      &info);
    info_written_ = true;
  }

  void clear_scratch(graph::PassContext& ctx, uint32_t words, bool whole) {
    scratch_clean_ = whole;
    VkCommandBuffer cmd = ctx.cmd();
    clear_pipeline_->bind(cmd);
    gpu::DescriptorWriter writer;
    writer.storage_buffer(0, *ctx.resource("scratch").buffer);
    writer.push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, clear_pipeline_->layout());
    clear_pipeline_->push_constants(cmd, VoxelClearPush{words});
    vkCmdDispatch(cmd, std::clamp<uint32_t>((words + 63) / 64, 1, 4096), 1, 1);
    ctx.barrier_within_pass("scratch");
  }

  void draw_objects(graph::PassContext& ctx, const gpu::GraphicsPipeline& pipeline,
                    const VoxelDrawPush& push,
                    const std::vector<const scene::GpuScene::Draw*>& draws, uint32_t edge) {
    VkCommandBuffer cmd = ctx.cmd();
    const scene::GpuScene& gpu_scene = ctx.gpu_scene();
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, {edge, edge}};
    rendering.layerCount = 1;
    vkCmdBeginRendering(cmd, &rendering);
    pipeline.bind(cmd);
    gpu::GraphicsPipeline::set_viewport(cmd, edge, edge);
    gpu::DescriptorWriter writer;
    writer.storage_buffer(0, *ctx.resource("scratch").buffer);
    writer.push(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.layout());
    VkDescriptorSet scene_set = gpu_scene.descriptor_set();
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.layout(), 1, 1,
                            &scene_set, 0, nullptr);
    pipeline.push_constants(cmd, push);
    VkDeviceSize offset = 0;
    VkBuffer vertices = gpu_scene.vertices().handle();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertices, &offset);
    vkCmdBindIndexBuffer(cmd, gpu_scene.indices().handle(), 0, VK_INDEX_TYPE_UINT32);
    for (const scene::GpuScene::Draw* draw : draws) {
      vkCmdDrawIndexed(cmd, draw->index_count, 1, draw->first_index, draw->vertex_offset,
                       draw->instance);
    }
    vkCmdEndRendering(cmd);
    ctx.barrier_within_pass("scratch");
  }

  void voxelize_chunk(graph::PassContext& ctx, const VoxelBox& chunk, const glm::ivec3& origin,
                      const std::vector<WorldBox>& instance_boxes) {
    VkCommandBuffer cmd = ctx.cmd();
    const uint32_t level = static_cast<uint32_t>(chunk.level);
    const double size = level_size(level);
    const glm::ivec3 extent = chunk.max - chunk.min;
    const uint32_t edge = static_cast<uint32_t>(std::max({extent.x, extent.y, extent.z}));
    const scene::GpuScene& gpu_scene = ctx.gpu_scene();

    std::vector<const scene::GpuScene::Draw*> draws;
    for (const scene::GpuScene::Draw& draw : gpu_scene.draws()) {
      if (draw.instance >= instance_boxes.size()) continue;
      const VoxelBox touched = window_box(chunk.level, instance_boxes[draw.instance], anchor_,
                                          origin, size, resolution_, 1);
      if (intersects(touched, chunk)) draws.push_back(&draw);
    }
    if (!draws.empty()) {
      VoxelDrawPush push{};
      push.anchor = glm::vec4(anchor_f_, 0.0f);
      push.level_min_size =
          glm::vec4(glm::vec3(glm::dvec3(origin) * size), static_cast<float>(size));
      push.box_min = glm::ivec4(chunk.min, static_cast<int>(edge));
      push.box_max = glm::ivec4(chunk.max, static_cast<int>(stride_));
      push.origin = glm::ivec4(origin, 0);
      // With stacked_surfaces = front the objects are drawn twice: first to find each voxel's
      // front surfaces, then to accumulate what they leave visible.
      if (front_pipeline_) draw_objects(ctx, *front_pipeline_, push, draws, edge);
      draw_objects(ctx, *draw_pipeline_, push, draws, edge);
    }

    resolve_pipeline_->bind(cmd);
    gpu::DescriptorWriter writer;
    writer.storage_buffer(0, *ctx.resource("scratch").buffer);
    writer.storage_image(1, ctx.resource("albedo").image->view(0), ctx.resource("albedo").layout);
    writer.storage_image(2, ctx.resource("normal").image->view(0), ctx.resource("normal").layout);
    if (has_emission_) {
      writer.storage_image(3, ctx.resource("emission").image->view(0),
                           ctx.resource("emission").layout);
    }
    if (has_faces_) {
      writer.storage_image(4, ctx.resource("faces").image->view(0), ctx.resource("faces").layout);
    }
    writer.push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, resolve_pipeline_->layout());
    VoxelResolvePush push{};
    push.box_min = glm::ivec4(chunk.min, chunk.level);
    push.box_max = glm::ivec4(chunk.max, static_cast<int>(resolution_));
    push.origin = glm::ivec4(origin, static_cast<int>(stride_));
    resolve_pipeline_->push_constants(cmd, push);
    vkCmdDispatch(cmd, gpu::ComputePipeline::groups(uint32_t(extent.x), 4),
                  gpu::ComputePipeline::groups(uint32_t(extent.y), 4),
                  gpu::ComputePipeline::groups(uint32_t(extent.z), 4));
    ctx.barrier_within_pass("scratch");
  }

  std::optional<gpu::GraphicsPipeline> draw_pipeline_, front_pipeline_;
  std::optional<gpu::ComputePipeline> resolve_pipeline_, clear_pipeline_;
  uint32_t resolution_ = 0, levels_ = 0, stride_ = kHdrWords;
  bool rgba8_ = false, has_emission_ = false, has_faces_ = false;
  int64_t capacity_voxels_ = 0;

  bool initialized_ = false;
  bool info_written_ = false;
  bool scratch_clean_ = false;  // the whole scratch buffer is zero
  double voxel_size_ = 1.0;
  glm::vec3 anchor_f_{0.0f};
  glm::dvec3 anchor_{0.0}, scene_center_{0.0};
  glm::dvec3 scene_min_{0.0}, scene_max_{0.0};  // bounds at initialization (window_center)
  std::vector<glm::ivec3> origins_;
  std::vector<bool> valid_;
  std::vector<DynamicInstance> dynamic_;
};

}  // namespace

void register_voxelize(graph::Registry& registry) {
  graph::PassTypeInfo info;
  info.type = "common.voxelize";
  info.doc =
      "Voxelizes the scene into clipmap volumes of albedo, normal and emission (conservative, "
      "one draw per object, atomics); revoxelizes only what a moving window or moving object "
      "made stale";
  const uint32_t draw_and_resolve = graph::kStageFragment | graph::kStageCompute;
  info.outputs = {
      {"clipmap_info",
       graph::kinds(ResourceKind::Buffer),
       Access::TransferWrite,
       graph::kStageTransfer,
       {},
       false,
       "VoxelClipmapInfo (contracts/voxel_clipmap.glsl, 288 bytes), written when a window moves"},
      {"albedo",
       graph::kinds(ResourceKind::Clipmap),
       Access::StorageReadWrite,
       graph::kStageCompute,
       {contracts::kVoxelAlbedoFormat},
       false,
       "rgb: linear diffuse albedo, a: opacity (0 empty)"},
      {"normal",
       graph::kinds(ResourceKind::Clipmap),
       Access::StorageReadWrite,
       graph::kStageCompute,
       {contracts::kVoxelNormalFormat},
       false,
       "xyz: averaged world normal (length <= 1, zero where faces cancel), w: 1 + d/4 where "
       "occupied (d: surface plane offset from the centre along the normal, voxels; "
       "contracts/voxel_volumes.glsl), 0 empty"},
      {"emission",
       graph::kinds(ResourceKind::Clipmap),
       Access::StorageReadWrite,
       graph::kStageCompute,
       {contracts::kVoxelEmissionFormat},
       true,
       "rgb: emitted radiance (HDR)"},
      {"faces",
       graph::kinds(ResourceKind::Clipmap),
       Access::StorageReadWrite,
       graph::kStageCompute,
       {contracts::kVoxelFacesFormat},
       true,
       "the surfaces grouped by the signed axis their normal leans along: per group the mean "
       "normal's direction and the share of the voxel's surface area "
       "(contracts/voxel_volumes.glsl), so injection lights each surface of a voxel with its "
       "own normal; all zero with average_rgba8, which keeps no per-facing sums (readers then "
       "light the voxel as one plane)"},
      {"scratch",
       graph::kinds(ResourceKind::Buffer),
       Access::StorageReadWrite,
       draw_and_resolve,
       {},
       false,
       "accumulation records (64 bytes per voxel with emission, 36 without, 12 for "
       "average_rgba8, 120 more with faces, 24 more with stacked_surfaces = front); R^3 records "
       "voxelize a level in one go, fewer split it",
       true},
  };
  info.params = {
      {"resolution",
       graph::ParamType::Int,
       0.0,
       0.0,
       1024.0,
       {},
       "voxels along a clipmap level's edge (a power of two, at least 8), for clipmaps the "
       "graph declares without a size; 0: the graph sizes them",
       false,
       true},
      {"levels",
       graph::ParamType::Int,
       0.0,
       0.0,
       double(contracts::kVoxelMaxLevels),
       {},
       "clipmap levels (1: one dense volume fitted to the scene), for clipmaps the graph "
       "declares without a size; 0: the graph sizes them",
       false,
       true},
      {"voxel_size",
       graph::ParamType::Float,
       0.0,
       0.0,
       1e5,
       {},
       "level-0 voxel edge (scene units); 0 = automatic: one level fits the scene bounds, L levels "
       "make the coarsest level's half-width span the scene's largest side (windows that follow "
       "the camera centre on it clamped into the scene bounds)",
       false},
      {"strategy",
       graph::ParamType::Enum,
       0.0,
       0.0,
       1.0,
       {"accumulate_hdr", "average_rgba8"},
       "accumulate_hdr: deterministic fixed-point sums, HDR emission; average_rgba8: the "
       "source documents' compare-and-swap RGBA8 moving average (8-bit, count saturates at 255)",
       false,
       true},
      {"stacked_surfaces",
       graph::ParamType::Enum,
       0.0,
       0.0,
       1.0,
       {"front", "average"},
       "front: of the surfaces in a voxel that face the same way, only the frontmost object "
       "(and what lies within 1/64 voxel of its plane) counts, so a lamp just under a ceiling "
       "voxelizes as the lamp (objects are drawn twice); average: every surface counts alike",
       false,
       true},
      {"conservative",
       graph::ParamType::Enum,
       0.0,
       0.0,
       3.0,
       {"auto", "geometry_shader", "hardware", "off"},
       "coverage: auto = hardware where the device has conservative rasterization, else "
       "triangles enlarged in the geometry shader; off = pixel centres only (leaves holes)",
       false},
      {"center",
       graph::ParamType::Enum,
       0.0,
       0.0,
       2.0,
       {"auto", "camera", "scene"},
       "what the windows centre on: auto = the scene for one level, the camera for several; "
       "camera = the camera clamped into the scene bounds (a camera outside the scene centres "
       "on the nearest point of its bounds, where the finest levels hold what it sees), each "
       "level moved as far into the bounds as its width allows",
       false},
  };
  graph::set_size_rule(info, "clipmap_info", [](const graph::SizeQuery&) {
    graph::DerivedSize size;
    size.bytes = contracts::kVoxelClipmapInfoBytes;
    return size;
  });
  for (const char* volume : {"albedo", "normal", "emission", "faces"}) {
    graph::set_size_rule(info, volume, clipmap_size);
  }
  graph::set_size_rule(info, "scratch", scratch_size);
  info.may_skip = true;
  info.validate = validate_voxelize;
  registry.add(std::move(info), [] { return std::make_unique<VoxelizePass>(); });
}

}  // namespace voxgi::passes::common
