#include "dvs_runner.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/image.hpp"
#include "engine/graph/graph_desc.hpp"
#include "engine/graph/plugin_loader.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

using graph::Access;
using graph::ResourceKind;

// Uploads the grid when its revision changed (like a voxelization that skips when nothing
// moved), else reports a skip so tests can see re-lighting without revoxelization.
class VoxelSourcePass final : public graph::Pass {
 public:
  explicit VoxelSourcePass(std::shared_ptr<VoxelSourceData> data) : data_(std::move(data)) {}

  std::string skip_reason(const graph::PassContext& ctx) const override {
    if (ctx.frame().first_frame || uploaded_ != data_->revision) return {};
    return "voxels unchanged";
  }

  void execute(graph::PassContext& ctx) override {
    if (!data_ || !data_->grid) throw std::runtime_error("dvs_test.voxel_source: no voxel grid");
    const VoxelGrid& grid = *data_->grid;
    staging_.clear();
    VkCommandBuffer cmd = ctx.cmd();
    const ClipmapInfoData& info = grid.info();
    gpu::Buffer& info_staging = stage(ctx, &info, sizeof(info));
    const VkBufferCopy region{0, 0, sizeof(info)};
    vkCmdCopyBuffer(cmd, info_staging.handle(), ctx.resource("clipmap_info").buffer->handle(), 1,
                    &region);
    const std::vector<uint8_t> albedo = grid.albedo_rgba8();
    copy_volume(ctx, "albedo", stage(ctx, albedo.data(), albedo.size()));
    const std::vector<uint16_t> normal = grid.normal_rgba16f();
    copy_volume(ctx, "normal", stage(ctx, normal.data(), normal.size() * 2));
    if (ctx.has("emission")) {
      const std::vector<uint16_t> emission = grid.emission_rgba16f();
      copy_volume(ctx, "emission", stage(ctx, emission.data(), emission.size() * 2));
    }
    uploaded_ = data_->revision;
  }

 private:
  gpu::Buffer& stage(const graph::PassContext& ctx, const void* data, size_t size) {
    staging_.push_back(std::make_unique<gpu::Buffer>(ctx.gpu(), size,
                                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                                     gpu::MemoryUsage::CpuToGpu, "voxel staging"));
    staging_.back()->upload(data, size);
    return *staging_.back();
  }

  static void copy_volume(const graph::PassContext& ctx, const char* slot,
                          const gpu::Buffer& staging) {
    const graph::BoundResource& r = ctx.resource(slot);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = r.info->extent;
    vkCmdCopyBufferToImage(ctx.cmd(), staging.handle(), r.image->handle(), r.layout, 1, &region);
  }

  std::shared_ptr<VoxelSourceData> data_;
  std::vector<std::unique_ptr<gpu::Buffer>> staging_;
  uint64_t uploaded_ = 0;
};

graph::SlotSpec volume_output(const char* name, VkFormat format, bool optional) {
  return {name,
          ResourceKind::Clipmap | ResourceKind::Image3D,
          Access::TransferWrite,
          graph::kStageTransfer,
          {format},
          optional,
          "uploaded voxels"};
}

}  // namespace

void register_voxel_source(graph::Registry& registry, std::shared_ptr<VoxelSourceData> data) {
  graph::PassTypeInfo info;
  info.type = "dvs_test.voxel_source";
  info.doc = "Uploads voxels built on the CPU (tests)";
  info.outputs = {
      {"clipmap_info",
       graph::kinds(ResourceKind::Buffer),
       Access::TransferWrite,
       graph::kStageTransfer,
       {},
       false,
       "VoxelClipmapInfo"},
      volume_output("albedo", VK_FORMAT_R8G8B8A8_UNORM, false),
      volume_output("normal", VK_FORMAT_R16G16B16A16_SFLOAT, false),
      volume_output("emission", VK_FORMAT_R16G16B16A16_SFLOAT, true),
  };
  info.may_skip = true;
  registry.add(std::move(info), [data] { return std::make_unique<VoxelSourcePass>(data); });
}

DvsRunner::DvsRunner(Setup setup) : setup_(std::move(setup)) {
  scene_ = setup_.scene;
  scene_.update_transforms();
  camera_ = scene_.cameras.empty() ? scene::default_camera(scene_) : scene_.cameras.front();
  const graph::GraphDesc desc =
      setup_.graph_text.empty()
          ? graph::load_graph_file(std::filesystem::path(VOXGI_SOURCE_DIR) / setup_.graph_path)
          : graph::parse_graph(setup_.graph_text, "dvs-test-graph.json");
  if (setup_.voxels) register_voxel_source(registry_, setup_.voxels);
  graph::PluginLoader loader(graph::PluginLoader::default_search_dirs());
  for (const std::string& family : desc.families()) {
    if (family != "dvs_test") loader.load_family(family, registry_);
  }
  compiled_ = graph::compile(
      desc, registry_, test_compile_options(scene_, setup_.width, setup_.height, setup_.overrides));
  gpu_ = std::make_unique<TestGraphGpu>(registry_, compiled_, scene_);
  frames_ = std::make_unique<runtime::FrameDriver>(*gpu_->executor);
}

DvsRunner::~DvsRunner() = default;

void DvsRunner::render(bool lights_changed, bool geometry_changed) {
  const float aspect = static_cast<float>(setup_.width) / static_cast<float>(setup_.height);
  frames_->render(runtime::frame_view(camera_, aspect), 0.0,
                  runtime::FrameChanges{false, lights_changed, geometry_changed});
}

void DvsRunner::move_light(size_t index, glm::vec3 position) {
  scene::Light& light = scene_.lights.at(index);
  scene_.nodes.at(static_cast<size_t>(light.node)).translation = position;
  scene_.update_transforms();
  gpu_->gpu_scene->update(scene_);
}

std::vector<float> DvsRunner::read(const std::string& output) {
  uint32_t w = 0, h = 0;
  return gpu_->executor->read_output(output, w, h);
}

std::string DvsRunner::skipped(const std::string& pass) const {
  for (const graph::Executor::PassTiming& t : gpu_->executor->timings()) {
    if (t.pass == pass) return t.skipped;
  }
  throw std::invalid_argument("no pass '" + pass + "' ran or skipped in the last frame");
}

bool DvsRunner::ran(const std::string& pass) const {
  return skipped(pass).empty();
}

}  // namespace voxgi::test
