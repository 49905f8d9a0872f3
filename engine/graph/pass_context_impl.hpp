#pragma once
// What a PassContext reads from: the executor fills one per live pass.

#include <map>
#include <string>
#include <vector>

#include "engine/graph/compiler.hpp"
#include "engine/graph/pass.hpp"

namespace voxgi::graph {

class PassContextImpl {
 public:
  gpu::Context* gpu = nullptr;
  gpu::ShaderCompiler* shaders = nullptr;
  const scene::Scene* scene = nullptr;
  scene::GpuScene* gpu_scene = nullptr;
  const FrameInfo* frame = nullptr;
  const CompiledPass* pass = nullptr;
  std::vector<BoundResource> bound;                          // parallel to pass->bindings
  const std::vector<uint64_t>* resource_versions = nullptr;  // by graph resource index
  bool params_changed = true;
  bool executing = false;
  VkCommandBuffer cmd = VK_NULL_HANDLE;

  // Throws std::invalid_argument naming the pass and the slot.
  size_t binding_index(std::string_view slot) const;
};

}  // namespace voxgi::graph
