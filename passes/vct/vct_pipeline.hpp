#pragma once
// Helpers the vct passes share: slot declarations, the filtered volume slots and the volume
// sampler (shaders, compute pipelines and input versions: engine/graph/pass_helpers.hpp).

#include <array>
#include <string>
#include <vector>

#include "engine/graph/pass.hpp"
#include "engine/graph/pass_helpers.hpp"

namespace voxgi::passes::vct {

// Slot declarations (compute stage).
graph::SlotSpec clipmap_info_input();
graph::SlotSpec sampled_clipmap(const char* name, const char* doc, bool optional,
                                std::vector<VkFormat> formats);

// The filtered volumes of lib/cone_trace.glsl: "filtered" (isotropic) or the six directional
// volumes, in the order +X, -X, +Y, -Y, +Z, -Z.
inline constexpr const char* kFilteredSlot = "filtered";
inline constexpr std::array<const char*, 6> kDirectionalSlots = {"pos_x", "neg_x", "pos_y",
                                                                 "neg_y", "pos_z", "neg_z"};

// The directional slots left unbound, comma-separated; empty when all six are bound.
std::string unbound_directional_slots(const graph::PassDeclaration& pass);
// Which filtered volumes a pass reads: the six directional ones when all are bound, else the
// isotropic one (check_filtered_volumes_bound makes sure one of the two is).
enum class FilteredVolumes { Isotropic, Anisotropic };
FilteredVolumes bound_filtered_volumes(const graph::PassDeclaration& pass);
// For validate hooks of passes reading the filtered volumes.
void check_filtered_volumes_bound(graph::PassCheck& check);

// The sampler lib/cone_trace.glsl needs for the filtered volumes: linear, whole mips,
// REPEAT, no anisotropic filtering. Owned by the pass that creates it.
class VolumeSampler {
 public:
  explicit VolumeSampler(gpu::Context& context);
  ~VolumeSampler();
  VolumeSampler(const VolumeSampler&) = delete;
  VolumeSampler& operator=(const VolumeSampler&) = delete;
  VkSampler handle() const { return sampler_; }

 private:
  gpu::Context& context_;
  VkSampler sampler_ = VK_NULL_HANDLE;
};

// Workgroup edge of the family's 2D compute shaders.
inline constexpr uint32_t kTile = 8;
inline uint32_t groups(uint32_t n, uint32_t local) {
  return (n + local - 1) / local;
}

}  // namespace voxgi::passes::vct
