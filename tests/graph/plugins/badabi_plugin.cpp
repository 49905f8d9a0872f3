// A plugin that claims a different ABI version: the loader must refuse it.
#include "engine/graph/pass.hpp"

VOXGI_PLUGIN_EXPORT uint32_t voxgi_plugin_abi_version() {
  return voxgi::graph::kPluginAbiVersion + 41;
}

VOXGI_PLUGIN_EXPORT void voxgi_plugin_register(voxgi::graph::Registry&) {}
