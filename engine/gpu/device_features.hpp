#pragma once
// What the chosen device can do beyond the required baseline, and the names graph files use
// for it in `when` conditions ("device.ray_query").

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace voxgi::gpu {

struct DeviceFeatures {
  // Supported and enabled: the renderer uses these where present.
  bool conservative_rasterization = false;  // VK_EXT_conservative_rasterization
  bool atomic_float_add_buffer = false;     // shaderBufferFloat32AtomicAdd
  bool atomic_float_add_image = false;      // shaderImageFloat32AtomicAdd
  bool geometry_shader = false;
  bool shader_int64 = false;
  bool timestamps = false;  // graphics+compute queue supports timestamps
  float timestamp_period_ns = 1.0f;
  uint32_t max_push_descriptors = 0;
  // Supported only: queried so graphs can choose passes by them, not enabled, because no pass
  // uses them yet. A pass that does must have the context enable them first.
  bool ray_tracing_pipeline = false;    // VK_KHR_ray_tracing_pipeline
  bool ray_query = false;               // VK_KHR_ray_query
  bool acceleration_structure = false;  // VK_KHR_acceleration_structure
  bool mesh_shader = false;             // VK_EXT_mesh_shader, mesh and task shaders
};

// One graph-file name of a device feature, "device.ray_query", with what it means.
struct DeviceFeatureName {
  std::string name;
  std::string doc;
};

// Every device feature a graph file may test, in a fixed order.
const std::vector<DeviceFeatureName>& device_feature_names();

// "device.ray_query" → 1 or 0 for every name of device_feature_names().
std::map<std::string, double> device_feature_values(const DeviceFeatures& features);

}  // namespace voxgi::gpu
