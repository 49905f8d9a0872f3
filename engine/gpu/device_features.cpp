#include "engine/gpu/device_features.hpp"

namespace voxgi::gpu {
namespace {

struct FeatureField {
  const char* name;
  const char* doc;
  bool DeviceFeatures::*field;
};

// The one list: names, docs and values come from it.
constexpr FeatureField kFeatures[] = {
    {"device.ray_tracing_pipeline", "ray tracing pipelines (VK_KHR_ray_tracing_pipeline)",
     &DeviceFeatures::ray_tracing_pipeline},
    {"device.ray_query", "ray queries from any shader stage (VK_KHR_ray_query)",
     &DeviceFeatures::ray_query},
    {"device.acceleration_structure",
     "hardware acceleration structures (VK_KHR_acceleration_structure)",
     &DeviceFeatures::acceleration_structure},
    {"device.conservative_rasterization",
     "conservative rasterization (VK_EXT_conservative_rasterization)",
     &DeviceFeatures::conservative_rasterization},
    {"device.shader_atomic_float", "float atomic add on storage buffers",
     &DeviceFeatures::atomic_float_add_buffer},
    {"device.shader_image_atomic_float", "float atomic add on storage images",
     &DeviceFeatures::atomic_float_add_image},
    {"device.shader_int64", "64-bit integers in shaders", &DeviceFeatures::shader_int64},
    {"device.geometry_shader", "geometry shaders", &DeviceFeatures::geometry_shader},
    {"device.mesh_shader", "mesh and task shaders (VK_EXT_mesh_shader)",
     &DeviceFeatures::mesh_shader},
    {"device.timestamps", "GPU timestamps on the graphics and compute queue",
     &DeviceFeatures::timestamps},
};

}  // namespace

const std::vector<DeviceFeatureName>& device_feature_names() {
  static const std::vector<DeviceFeatureName> names = [] {
    std::vector<DeviceFeatureName> list;
    for (const FeatureField& f : kFeatures) list.push_back({f.name, f.doc});
    return list;
  }();
  return names;
}

std::map<std::string, double> device_feature_values(const DeviceFeatures& features) {
  std::map<std::string, double> values;
  for (const FeatureField& f : kFeatures) values[f.name] = features.*(f.field) ? 1.0 : 0.0;
  return values;
}

}  // namespace voxgi::gpu
