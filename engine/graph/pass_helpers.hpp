#pragma once
// Helpers for writing passes that every family shares: compiling a family's shaders, compute
// pipelines with push descriptors (and optionally the scene's set), binding the scene's set,
// and remembering input versions for skip decisions.

#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "engine/gpu/pipeline.hpp"
#include "engine/gpu/shader_compiler.hpp"
#include "engine/graph/pass.hpp"

namespace voxgi::graph {

// Compiles shaders/<path> (e.g. "vct/filter.comp") with the given defines.
std::vector<uint32_t> compile_pass_shader(const PassContext& ctx, const std::string& path,
                                          std::vector<gpu::ShaderDefine> defines = {});

// A compute pipeline from shaders/<path>: set 0 holds `bindings` (push descriptors, compute
// stage), set 1 the scene's descriptor set when `with_scene_set` is true. Named after the pass.
gpu::ComputePipeline make_pass_compute(const PassContext& ctx, const std::string& path,
                                       std::vector<gpu::Binding> bindings,
                                       uint32_t push_constant_size, bool with_scene_set,
                                       std::vector<gpu::ShaderDefine> defines = {});

// A 2D image read through a sampler in compute (any format unless `formats` is given).
SlotSpec sampled_2d_input(const char* name, const char* doc, bool optional = false,
                          std::vector<VkFormat> formats = {});

// A clipmap read through a sampler in compute (any format unless `formats` is given).
SlotSpec sampled_clipmap_input(const char* name, const char* doc, bool optional = false,
                               std::vector<VkFormat> formats = {});

// A storage buffer read or written by a compute shader (`scratch`: see SlotSpec).
SlotSpec compute_buffer_slot(const char* name, Access access, const char* doc,
                             bool scratch = false);

// Workgroups of `local` invocations that cover `n` invocations along one axis.
inline uint32_t workgroups(uint64_t n, uint32_t local) {
  return static_cast<uint32_t>((n + local - 1) / local);
}

// A bound resource's extent at the mip its slot is bound to.
VkExtent3D bound_extent(const ResourceInfo& info);

// For validate hooks. Voxel volumes are addressed texel for texel: reports each bound slot of
// `slots` whose extent or clipmap levels differ from those of the slot `reference`.
void check_same_clipmap_layout(PassCheck& check, std::string_view reference,
                               std::initializer_list<const char*> slots);

// Binds the scene's descriptor set as set 1 of a compute pipeline.
void bind_scene_set(const PassContext& ctx, const gpu::ComputePipeline& pipeline);

// Remembers the resource versions (PassContext::resource_version) of a pass's input slots at
// its last execute(), so that skip_reason() can tell whether any of them has been written
// since. An unbound optional slot counts as version 0.
class InputVersions {
 public:
  explicit InputVersions(std::vector<std::string> slots) : slots_(std::move(slots)) {}
  // True before the first remember(), after forget(), and whenever a slot's version differs
  // from the remembered one.
  bool changed(const PassContext& ctx) const;
  void remember(const PassContext& ctx);
  void forget() { valid_ = false; }

 private:
  std::vector<uint64_t> current(const PassContext& ctx) const;
  std::vector<std::string> slots_;
  std::vector<uint64_t> seen_;
  bool valid_ = false;
};

}  // namespace voxgi::graph
