// Entry points of the "dvs" (deferred voxel shading) pass family plugin.

#include "engine/graph/pass.hpp"
#include "passes/dvs/passes.hpp"

VOXGI_PLUGIN_EXPORT uint32_t voxgi_plugin_abi_version() {
  return voxgi::graph::kPluginAbiVersion;
}

VOXGI_PLUGIN_EXPORT void voxgi_plugin_register(voxgi::graph::Registry& registry) {
  using namespace voxgi::passes::dvs;
  register_voxel_lighting(registry);
  register_voxel_bounce(registry);
}
