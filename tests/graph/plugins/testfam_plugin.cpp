// A pass family for the plugin loader tests: one pass type, "testfam.copy".
#include <memory>

#include "engine/graph/pass.hpp"

namespace {

class CopyPass : public voxgi::graph::Pass {
 public:
  void execute(voxgi::graph::PassContext&) override {}
};

}  // namespace

VOXGI_PLUGIN_EXPORT uint32_t voxgi_plugin_abi_version() {
  return voxgi::graph::kPluginAbiVersion;
}

VOXGI_PLUGIN_EXPORT void voxgi_plugin_register(voxgi::graph::Registry& registry) {
  using namespace voxgi::graph;
  PassTypeInfo info;
  info.type = "testfam.copy";
  info.doc = "copies src to dst";
  SlotSpec src;
  src.name = "src";
  src.kinds = kinds(ResourceKind::Image2D);
  src.access = Access::Sampled;
  SlotSpec dst;
  dst.name = "dst";
  dst.kinds = kinds(ResourceKind::Image2D);
  dst.access = Access::StorageWrite;
  dst.stages = kStageCompute;
  info.inputs = {src};
  info.outputs = {dst};
  registry.add(info, [] { return std::make_unique<CopyPass>(); });
}
