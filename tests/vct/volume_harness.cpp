#include "tests/vct/volume_harness.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/graph/graph_desc.hpp"
#include "engine/graph/plugin_loader.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {

glm::ivec3 clipmap_texel(const ClipmapInfo& info, glm::ivec3 window, int level) {
  const int r = static_cast<int>(info.dims.x);
  const glm::ivec3 world = window + glm::ivec3(info.levels[level].origin_voxel);
  const glm::ivec3 wrapped = ((world % r) + r) % r;
  return {wrapped.x, wrapped.y, wrapped.z + level * r};
}

glm::vec4 faces_texel(const std::vector<std::pair<int, uint32_t>>& groups) {
  glm::uvec4 faces(0u);
  for (const auto& [g, steps] : groups) {
    // Group g's axis as its normal (both cube-face coordinates 0: code 31 of 0..62) and its
    // plane through the voxel centre (offset code 7 of 0..14).
    const uint32_t code = 31u | (31u << 6) | (7u << 12);
    faces[g >> 1] |= code << (16 * (g & 1));
    faces.w |= steps << (5 * g);
  }
  return glm::vec4(glm::uintBitsToFloat(faces.x), glm::uintBitsToFloat(faces.y),
                   glm::uintBitsToFloat(faces.z), glm::uintBitsToFloat(faces.w));
}

ClipmapInfo make_clipmap_info(int resolution, int levels, float base_voxel, glm::vec3 centre,
                              glm::vec3 anchor) {
  ClipmapInfo info{};
  info.anchor = glm::vec4(anchor, 0.0f);
  info.dims = glm::uvec4(static_cast<uint32_t>(resolution), static_cast<uint32_t>(levels), 0, 0);
  for (int l = 0; l < levels; ++l) {
    const float size = base_voxel * std::exp2(static_cast<float>(l));
    const glm::ivec3 origin =
        glm::ivec3(glm::round((centre - anchor) / size)) - glm::ivec3(resolution / 2);
    info.levels[l].origin_voxel = glm::ivec4(origin, 1);
    info.levels[l].min_corner_size = glm::vec4(glm::vec3(origin) * size, size);
  }
  return info;
}

namespace {

class VolumePass final : public graph::Pass {
 public:
  explicit VolumePass(const VolumeData* data) : data_(data) {}

  std::string skip_reason(const graph::PassContext&) const override {
    return uploaded_ == data_->version ? "volumes unchanged" : std::string();
  }

  void execute(graph::PassContext& ctx) override {
    staging_.clear();
    VkCommandBuffer cmd = ctx.cmd();
    vkCmdUpdateBuffer(cmd, ctx.resource("clipmap_info").buffer->handle(), 0, sizeof(ClipmapInfo),
                      &data_->info);
    for (const char* slot : {"albedo", "normal", "emission", "faces", "light_shares", "radiance"}) {
      if (!ctx.has(slot)) continue;
      auto it = data_->volumes.find(slot);
      if (it == data_->volumes.end()) {
        throw std::invalid_argument(std::string("vcttest.volumes: no data for slot ") + slot);
      }
      const graph::BoundResource& out = ctx.resource(slot);
      const std::vector<uint8_t> bytes = encode(it->second, out.info->format);
      const VkExtent3D e = out.info->extent;
      if (it->second.texels.size() != size_t(e.width) * e.height * e.depth) {
        throw std::invalid_argument(std::string("vcttest.volumes: wrong size for ") + slot);
      }
      staging_.push_back(std::make_unique<gpu::Buffer>(ctx.gpu(), bytes.size(),
                                                       VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                                       gpu::MemoryUsage::CpuToGpu, "staging"));
      staging_.back()->upload(bytes.data(), bytes.size());
      VkBufferImageCopy region{};
      region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      region.imageExtent = e;
      vkCmdCopyBufferToImage(cmd, staging_.back()->handle(), out.image->handle(), out.layout, 1,
                             &region);
    }
    uploaded_ = data_->version;
  }

 private:
  static std::vector<uint8_t> encode(const CpuClipmap& volume, VkFormat format) {
    std::vector<uint8_t> bytes;
    for (const glm::vec4& v : volume.texels) {
      if (format == VK_FORMAT_R8G8B8A8_UNORM) {
        for (int c = 0; c < 4; ++c) {
          bytes.push_back(static_cast<uint8_t>(std::lround(glm::clamp(v[c], 0.0f, 1.0f) * 255.0f)));
        }
      } else if (format == VK_FORMAT_R16G16B16A16_SFLOAT) {
        for (int c = 0; c < 4; ++c) {
          const uint16_t h = glm::packHalf1x16(v[c]);
          bytes.push_back(static_cast<uint8_t>(h & 0xff));
          bytes.push_back(static_cast<uint8_t>(h >> 8));
        }
      } else if (format == VK_FORMAT_R32G32B32A32_SFLOAT || format == VK_FORMAT_R32G32B32A32_UINT) {
        // Integer texels travel as the floats' bits (see CpuClipmap).
        const size_t at = bytes.size();
        bytes.resize(at + 16);
        std::memcpy(bytes.data() + at, &v, 16);
      } else if (format == VK_FORMAT_R32_UINT) {
        const size_t at = bytes.size();
        bytes.resize(at + 4);
        std::memcpy(bytes.data() + at, &v.x, 4);
      } else {
        throw std::invalid_argument("vcttest.volumes: unsupported format");
      }
    }
    return bytes;
  }

  const VolumeData* data_;
  uint64_t uploaded_ = 0;
  std::vector<std::unique_ptr<gpu::Buffer>> staging_;
};

graph::SlotSpec transfer_output(const char* name, graph::ResourceKinds kinds, bool optional) {
  return {name, kinds, graph::Access::TransferWrite, graph::kStageTransfer, {}, optional, name};
}

}  // namespace

void register_volume_pass(graph::Registry& registry, const VolumeData* data) {
  graph::PassTypeInfo info;
  info.type = "vcttest.volumes";
  info.doc = "test: uploads CPU clipmaps";
  const graph::ResourceKinds clipmap = graph::kinds(graph::ResourceKind::Clipmap);
  info.outputs = {transfer_output("clipmap_info", graph::kinds(graph::ResourceKind::Buffer), false),
                  transfer_output("albedo", clipmap, true),
                  transfer_output("normal", clipmap, true),
                  transfer_output("emission", clipmap, true),
                  transfer_output("faces", clipmap, true),
                  transfer_output("light_shares", clipmap, true),
                  transfer_output("radiance", clipmap, true)};
  info.may_skip = true;
  registry.add(std::move(info), [data] { return std::make_unique<VolumePass>(data); });
}

VolumeGraph::VolumeGraph(const std::string& graph_json, const VolumeData* data, scene::Scene scene,
                         uint32_t width, uint32_t height,
                         std::map<std::string, std::string> overrides)
    : scene_(std::move(scene)), width_(width), height_(height) {
  graph::PluginLoader loader(graph::PluginLoader::default_search_dirs());
  loader.load_family("common", registry_);
  loader.load_family("vct", registry_);
  register_volume_pass(registry_, data);
  scene_.update_transforms();
  const graph::GraphDesc desc = graph::parse_graph(graph_json, "vct_test_graph.json");
  graph::CompileOptions options;
  options.viewport_width = width;
  options.viewport_height = height;
  options.scene_features = scene_.features().as_map();
  options.overrides = std::move(overrides);
  compiled_ = graph::compile(desc, registry_, options);
  gpu::Context& context = gpu_context();
  shaders_ = std::make_unique<gpu::ShaderCompiler>(
      std::vector<std::filesystem::path>{
          std::filesystem::path(VOXGI_SOURCE_DIR) / "shaders",
          std::filesystem::path(VOXGI_SOURCE_DIR) / "tests" / "vct" / "shaders"},
      gpu::ShaderCompiler::default_cache_dir());
  gpu_scene_ = std::make_unique<scene::GpuScene>(context, scene_);
  executor_ = std::make_unique<graph::Executor>(context, *shaders_, registry_);
  executor_->build(compiled_, scene_, *gpu_scene_);
  frames_ = std::make_unique<runtime::FrameDriver>(*executor_);
}

VolumeGraph::~VolumeGraph() = default;

void VolumeGraph::set_camera(glm::vec3 eye, glm::vec3 target) {
  eye_ = eye;
  target_ = target;
}

void VolumeGraph::render(int frames, bool lights_changed) {
  scene::Camera camera;
  camera.yfov = glm::radians(60.0f);
  camera.znear = 0.01f;
  camera.zfar = 500.0f;
  const float aspect = static_cast<float>(width_) / static_cast<float>(height_);
  for (int i = 0; i < frames; ++i) {
    frames_->render(runtime::look_at_view(eye_, target_, camera, aspect), 0.0,
                    runtime::FrameChanges{false, lights_changed, false});
  }
}

std::string VolumeGraph::skipped(const std::string& pass) const {
  for (const auto& t : executor_->timings()) {
    if (t.pass == pass) return t.skipped;
  }
  throw std::invalid_argument("no pass " + pass + " in the last frame");
}

std::vector<glm::vec4> VolumeGraph::download(const std::string& resource, uint32_t mip) {
  const int r = compiled_.find_resource(resource);
  if (r < 0) throw std::invalid_argument("no resource " + resource);
  const graph::CompiledResource& res = compiled_.resources[static_cast<size_t>(r)];
  gpu::Image* image = executor_->image(resource);
  if (!image) throw std::invalid_argument("resource " + resource + " has no image");
  const VkImageLayout layout = res.end_state.at(mip).layout;
  const std::vector<uint8_t> bytes = image->download(layout, mip);
  std::vector<glm::vec4> texels;
  const VkFormat format = image->format();
  if (format == VK_FORMAT_R16G16B16A16_SFLOAT) {
    for (size_t i = 0; i + 8 <= bytes.size(); i += 8) {
      glm::vec4 v;
      for (int c = 0; c < 4; ++c) {
        const uint16_t h = static_cast<uint16_t>(bytes[i + 2 * c] | (bytes[i + 2 * c + 1] << 8));
        v[c] = glm::unpackHalf1x16(h);
      }
      texels.push_back(v);
    }
  } else if (format == VK_FORMAT_R8G8B8A8_UNORM || format == VK_FORMAT_R8G8B8A8_SRGB) {
    for (size_t i = 0; i + 4 <= bytes.size(); i += 4) {
      texels.push_back(glm::vec4(bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]) / 255.0f);
    }
  } else if (format == VK_FORMAT_R32_UINT) {
    // Integer texels travel as the floats' bits (see CpuClipmap), in x.
    for (size_t i = 0; i + 4 <= bytes.size(); i += 4) {
      float bits;
      std::memcpy(&bits, bytes.data() + i, 4);
      texels.push_back(glm::vec4(bits, 0.0f, 0.0f, 0.0f));
    }
  } else {
    throw std::invalid_argument("download: unsupported format of " + resource);
  }
  return texels;
}

namespace {

// The sampler contracts/cone_trace.glsl expects (as passes/vct/vct_pipeline.cpp creates it).
class ProbeSampler {
 public:
  explicit ProbeSampler(gpu::Context& context) : context_(context) {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = info.minFilter = VK_FILTER_LINEAR;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    info.maxLod = VK_LOD_CLAMP_NONE;
    if (vkCreateSampler(context_.device(), &info, nullptr, &sampler_) != VK_SUCCESS) {
      throw std::runtime_error("vkCreateSampler failed");
    }
  }
  ~ProbeSampler() { vkDestroySampler(context_.device(), sampler_, nullptr); }
  ProbeSampler(const ProbeSampler&) = delete;
  ProbeSampler& operator=(const ProbeSampler&) = delete;
  VkSampler handle() const { return sampler_; }

 private:
  gpu::Context& context_;
  VkSampler sampler_ = VK_NULL_HANDLE;
};

struct ProbeGpu {
  glm::vec4 position;
  glm::vec4 direction;
};
struct ProbePush {
  int32_t single_cone;
  int32_t diffuse_cones;
  float tan_half_angle;
  float step_factor;
  float max_distance;
  float ao_falloff;
  float normal_offset;
  float start_distance;
  uint32_t count;
  int32_t lanes;
};

}  // namespace

std::vector<ProbeResult> run_probes(VolumeGraph& graph, const std::string& info_resource,
                                    const std::vector<std::string>& volume_resources,
                                    const std::vector<Probe>& probes, const ProbeSettings& s) {
  gpu::Context& context = gpu_context();
  gpu::PipelineLayoutDesc layout;
  const uint32_t volumes = static_cast<uint32_t>(volume_resources.size());
  layout.bindings = {
      {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
      {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT, volumes},
      {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
      {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}};
  layout.push_constant_size = sizeof(ProbePush);
  layout.push_constant_stages = VK_SHADER_STAGE_COMPUTE_BIT;
  gpu::ShaderRequest request;
  request.path = "probe.comp";
  request.defines = {{"VCT_ANISOTROPIC", volumes == 6 ? "1" : "0"}};
  gpu::ComputePipeline pipeline(context, graph.shaders().compile(request), layout, "vct probe");

  std::vector<ProbeGpu> in;
  for (const Probe& p : probes) in.push_back({glm::vec4(p.position, 1), glm::vec4(p.direction, 0)});
  gpu::Buffer in_buffer(context, in.size() * sizeof(ProbeGpu), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                        gpu::MemoryUsage::CpuToGpu, "probes");
  in_buffer.upload(in.data(), in.size() * sizeof(ProbeGpu));
  gpu::Buffer out_buffer(context, probes.size() * sizeof(glm::vec4),
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::GpuToCpu,
                         "probe results");
  gpu::Buffer* info = graph.executor().buffer(info_resource);
  if (!info) throw std::invalid_argument("no buffer " + info_resource);
  std::vector<VkDescriptorImageInfo> images;
  const ProbeSampler probe_sampler(context);
  const VkSampler sampler = probe_sampler.handle();
  for (const std::string& name : volume_resources) {
    gpu::Image* image = graph.executor().image(name);
    if (!image) throw std::invalid_argument("no image " + name);
    const int r = graph.compiled().find_resource(name);
    const VkImageLayout layout_now =
        graph.compiled().resources[static_cast<size_t>(r)].end_state.at(0).layout;
    images.push_back({sampler, image->view(), layout_now});
  }
  const ProbePush push{s.lane_layout   ? 2
                       : s.single_cone ? 1
                                       : 0,
                       s.diffuse_cones,
                       s.tan_half_angle,
                       s.step_factor,
                       s.max_distance,
                       s.ao_falloff,
                       s.normal_offset,
                       s.start_distance,
                       static_cast<uint32_t>(probes.size()),
                       s.lanes};
  // Graph outputs end the frame ready for read-back; sample them in GENERAL and put them back.
  std::vector<std::pair<gpu::Image*, VkImageLayout>> moved;
  for (size_t i = 0; i < images.size(); ++i) {
    if (images[i].imageLayout == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL ||
        images[i].imageLayout == VK_IMAGE_LAYOUT_GENERAL) {
      continue;
    }
    moved.emplace_back(graph.executor().image(volume_resources[i]), images[i].imageLayout);
    images[i].imageLayout = VK_IMAGE_LAYOUT_GENERAL;
  }
  context.immediate_submit([&](VkCommandBuffer cmd) {
    for (auto& [image, layout_was] : moved) {
      image->transition(cmd, layout_was, VK_IMAGE_LAYOUT_GENERAL);
    }
    pipeline.bind(cmd);
    gpu::DescriptorWriter()
        .storage_buffer(0, *info)
        .image_array(1, images)
        .storage_buffer(2, in_buffer)
        .storage_buffer(3, out_buffer)
        .push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout());
    pipeline.push_constants(cmd, push);
    vkCmdDispatch(cmd, gpu::ComputePipeline::groups(static_cast<uint32_t>(probes.size()), 64), 1,
                  1);
    for (auto& [image, layout_was] : moved) {
      image->transition(cmd, VK_IMAGE_LAYOUT_GENERAL, layout_was);
    }
  });
  std::vector<glm::vec4> raw(probes.size());
  std::memcpy(raw.data(), out_buffer.mapped(), raw.size() * sizeof(glm::vec4));
  std::vector<ProbeResult> results;
  for (const glm::vec4& v : raw) results.push_back({glm::vec3(v), v.w});
  return results;
}

}  // namespace voxgi::test
