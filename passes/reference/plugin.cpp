// Entry points of the "reference" pass family plugin.

#include "engine/graph/pass.hpp"
#include "passes/reference/passes.hpp"

VOXGI_PLUGIN_EXPORT uint32_t voxgi_plugin_abi_version() {
  return voxgi::graph::kPluginAbiVersion;
}

VOXGI_PLUGIN_EXPORT void voxgi_plugin_register(voxgi::graph::Registry& registry) {
  voxgi::passes::reference::register_path_tracer(registry);
}
