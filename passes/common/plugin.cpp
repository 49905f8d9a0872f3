// Entry points of the "common" pass family plugin.

#include "engine/graph/pass.hpp"
#include "passes/common/passes.hpp"

VOXGI_PLUGIN_EXPORT uint32_t voxgi_plugin_abi_version() {
  return voxgi::graph::kPluginAbiVersion;
}

VOXGI_PLUGIN_EXPORT void voxgi_plugin_register(voxgi::graph::Registry& registry) {
  using namespace voxgi::passes::common;
  register_gbuffer(registry);
  register_shadow_maps(registry);
  register_deferred_lighting(registry);
  register_ambient(registry);
  register_composite(registry);
  register_display_transform(registry);
  register_voxelize(registry);
}
