// Entry points of the "vct" pass family plugin: light injection into the voxel radiance
// clipmap, its (anisotropic) filtering, and cone tracing for indirect diffuse, AO and specular.

#include "engine/graph/pass.hpp"
#include "passes/vct/passes.hpp"

VOXGI_PLUGIN_EXPORT uint32_t voxgi_plugin_abi_version() {
  return voxgi::graph::kPluginAbiVersion;
}

VOXGI_PLUGIN_EXPORT void voxgi_plugin_register(voxgi::graph::Registry& registry) {
  using namespace voxgi::passes::vct;
  register_inject(registry);
  register_filter(registry);
  register_cone_trace(registry);
  register_cone_trace_specular(registry);
}
