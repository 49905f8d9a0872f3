#pragma once
// Small helpers the family's passes share: compiling their shaders and dispatch sizes.

#include <string>
#include <vector>

#include "engine/gpu/pipeline.hpp"
#include "engine/gpu/shader_compiler.hpp"
#include "engine/graph/pass.hpp"

namespace voxgi::passes::common {

// Compiles shaders/common/<file> with the given defines.
std::vector<uint32_t> compile_common_shader(const graph::PassContext& ctx, const std::string& file,
                                            std::vector<gpu::ShaderDefine> defines = {});

// A compute pipeline from shaders/common/<file>: set 0 holds `bindings` (push descriptors),
// set 1 the scene's descriptor set when `with_scene_set` is true.
gpu::ComputePipeline make_common_compute(const graph::PassContext& ctx, const std::string& file,
                                         std::vector<gpu::Binding> bindings,
                                         uint32_t push_constant_size, bool with_scene_set,
                                         std::vector<gpu::ShaderDefine> defines = {});

// Binds the scene's descriptor set as set 1 of a compute pipeline.
void bind_scene_set(const graph::PassContext& ctx, const gpu::ComputePipeline& pipeline);

// Slot declarations the family's compute passes share.
// A 2D image read through a sampler in compute (any format unless `formats` is given).
graph::SlotSpec sampled_input(const char* name, const char* doc, bool optional = false,
                              std::vector<VkFormat> formats = {});
// A 2D HDR radiance image (rgba16f or rgba32f) written as a storage image in compute.
graph::SlotSpec radiance_output(const char* name, const char* doc);

// Workgroup size of the family's 2D compute shaders (local_size_x = local_size_y).
inline constexpr uint32_t kTile = 8;

// Dispatches a kTile x kTile compute shader over a width x height image.
void dispatch_over_image(VkCommandBuffer cmd, uint32_t width, uint32_t height);

// Push-constant block for the family's full-screen compute passes.
struct ImageSize {
  uint32_t width;
  uint32_t height;
};

}  // namespace voxgi::passes::common
