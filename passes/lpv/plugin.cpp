// Entry points of the "lpv" (light propagation volumes) pass family plugin.

#include "engine/graph/pass.hpp"
#include "passes/lpv/passes.hpp"

VOXGI_PLUGIN_EXPORT uint32_t voxgi_plugin_abi_version() {
  return voxgi::graph::kPluginAbiVersion;
}

VOXGI_PLUGIN_EXPORT void voxgi_plugin_register(voxgi::graph::Registry& registry) {
  using namespace voxgi::passes::lpv;
  register_rsm(registry);
  register_inject(registry);
  register_downsample(registry);
  register_propagate(registry);
  register_merge(registry);
  register_lookup(registry);
}
