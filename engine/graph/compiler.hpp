#pragma once
// Graph description → compiled graph: validated, culled, ordered, with resource lifetimes,
// shared physical resources, layouts and barriers. Pure CPU work; nothing touches a device.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "engine/graph/diagnostics.hpp"
#include "engine/graph/graph_desc.hpp"
#include "engine/graph/pass.hpp"

namespace voxgi::graph {

struct CompileOptions {
  uint32_t viewport_width = 1280;
  uint32_t viewport_height = 720;
  std::map<std::string, double> scene_features;  // "scene.has_emissive" → 1
  // The device the graph will run on: "device.ray_query" → 1 (gpu::device_feature_values) and
  // its name. Empty when compiling without a device (`voxgi graph check`): every device feature
  // then reads as absent, and the reasons of passes culled by one say so.
  std::map<std::string, double> device_features;
  std::string device_name;
  // --set key=value; "variant" selects one of the graph's variants, whose settings apply first.
  std::map<std::string, std::string> overrides;
  bool full_barriers = false;    // a full memory barrier before every pass (rules out sync bugs)
  bool alias_transients = true;  // let same-description transients with disjoint lives share
};

// Where a resource (or some of its mips) is, as far as synchronisation goes.
struct ResourceState {
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = VK_ACCESS_2_NONE;
};

// One image or buffer barrier, in the shape of VkImageMemoryBarrier2 / VkBufferMemoryBarrier2.
// resource == -1 with is_global: a VkMemoryBarrier2 (full_barriers mode).
struct Barrier {
  int resource = -1;  // index into CompiledGraph::resources
  bool is_buffer = false;
  bool is_global = false;
  uint32_t base_mip = 0;
  uint32_t mip_count = 1;
  VkPipelineStageFlags2 src_stages = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 src_access = VK_ACCESS_2_NONE;
  VkPipelineStageFlags2 dst_stages = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 dst_access = VK_ACCESS_2_NONE;
  VkImageLayout old_layout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImageLayout new_layout = VK_IMAGE_LAYOUT_UNDEFINED;
};

struct SlotBinding {
  std::string slot;
  bool is_input = true;
  const SlotSpec* spec = nullptr;
  int resource = -1;    // -1: an optional slot left unbound
  ResourceInfo info;    // the resource as the slot sees it (mip set for "@N")
  ResourceState state;  // layout, stages and access the pass needs
  SourceLoc loc;
};

struct CompiledPass {
  std::string name;
  std::string type;
  const PassTypeInfo* type_info = nullptr;
  size_t file_index = 0;  // position in the graph file
  SourceLoc loc;
  std::map<std::string, ParamValue> params;  // every declared parameter, resolved
  std::vector<SlotBinding> bindings;         // inputs then outputs, in declaration order
  std::vector<Barrier> barriers;             // recorded before the pass
  std::vector<size_t> depends_on;            // schedule indices of passes it must follow

  const SlotBinding* binding(std::string_view slot) const;
};

// True when skipping the pass would leave this binding's resource undefined: an output it
// writes (not scratch) bound to a transient resource. A pass may skip only when no binding is.
bool skip_leaves_undefined(const SlotBinding& binding);

// What the validate hook of the pass's type reports (nothing when it has none), each problem
// naming the pass and the field ("params.resolution", "out.half_res"), without a location.
std::vector<Diagnostic> validate_pass(const CompiledPass& pass);

// A pass `when` condition that reads device features: which ones, and what it decided.
struct DeviceCondition {
  std::string pass;
  std::string when;
  std::vector<std::string> features;  // "device.ray_query", in order of appearance
  bool value = false;                 // true: the pass is live as far as `when` goes
};

struct CulledPass {
  std::string name;
  std::string type;
  size_t file_index = 0;
  SourceLoc loc;
  std::string reason;
};

struct CompiledResource {
  ResourceInfo info;  // whole resource (mip == -1)
  SourceLoc loc;
  VkImageUsageFlags image_usage = 0;
  VkBufferUsageFlags buffer_usage = 0;
  int physical = -1;    // index into CompiledGraph::physical; -1 when no live pass uses it
  int first_pass = -1;  // schedule indices of the first and last live pass touching it
  int last_pass = -1;
  uint64_t bytes = 0;  // estimated
  bool is_output = false;
  std::string derived_by;  // the pass whose slot derived the size, when the graph gave none
  // Frame history ("name@previous"): the persistent copy of `history_of` as the previous frame
  // left it, written by a copy at the end of every frame; `history` is the other direction.
  int history_of = -1;
  int history = -1;
  // Carried between frames: persistent. A transient's first use in a frame writes it.
  bool carries_contents = false;
  // State per mip (one entry for buffers) at the end of a frame, after output transitions.
  std::vector<ResourceState> end_state;
};

// One allocation; several transient resources may share it.
struct PhysicalResource {
  ResourceInfo info;  // description (the first sharer's name)
  VkImageUsageFlags image_usage = 0;
  VkBufferUsageFlags buffer_usage = 0;
  std::vector<int> resources;  // the logical resources living in it, by first use
  uint64_t bytes = 0;
  bool carries_contents = false;
  int memory_block = -1;  // index into CompiledGraph::memory_blocks; -1: memory of its own
};

// Memory that transient allocations with disjoint lives in a frame take in turn (aliasing),
// whatever their descriptions; the executor sizes it from the device's requirements.
struct MemoryBlock {
  std::vector<int> physical;  // in order of first use in a frame
  uint64_t bytes = 0;         // estimated: the largest member
};

// A frame-history copy at the end of every frame: resource `from` into its "@previous" twin.
struct HistoryCopy {
  int from = -1;
  int to = -1;
};

struct CompiledGraph {
  std::string file;
  std::string name;
  uint32_t viewport_width = 0;
  uint32_t viewport_height = 0;
  bool full_barriers = false;
  std::map<std::string, double> parameters;  // graph parameters after overrides
  std::string variant;                       // the variant compiled; empty: the file as written
  std::vector<std::string> variants;         // every variant the file names
  // Device features as conditions read them, and whether they came from a device (false:
  // compiled without one, every feature absent).
  std::map<std::string, double> device_features;
  bool device_queried = false;
  std::string device_name;
  std::vector<DeviceCondition> device_conditions;  // in file order
  std::vector<CompiledPass> passes;                // live, in execution order
  std::vector<CulledPass> culled;                  // in file order
  std::vector<CompiledResource> resources;         // in file order
  std::vector<PhysicalResource> physical;
  // Carried resources: from their end-of-frame state to the state of their first use.
  std::vector<Barrier> frame_start;
  // Outputs to TRANSFER_SRC at the end of the frame so they can be read back.
  std::vector<Barrier> frame_end;
  std::map<std::string, int> outputs;  // output name → resource index
  std::vector<MemoryBlock> memory_blocks;
  std::vector<HistoryCopy> history_copies;  // recorded after the last pass, in this order
  std::vector<Barrier> history_barriers;    // before them, in a frame of all passes
  uint64_t total_bytes = 0;           // physical allocations, aliased ones counted once per block
  uint64_t total_bytes_unshared = 0;  // if nothing shared

  int find_resource(std::string_view name) const;
  const CompiledPass* find_pass(std::string_view name) const;
  const CulledPass* find_culled(std::string_view name) const;
};

// Fills options.device_features and device_name from the device the graph will run on.
void use_device(CompileOptions& options, const gpu::Context& context);

// Throws GraphError listing every problem found, each once.
CompiledGraph compile(const GraphDesc& desc, const Registry& registry,
                      const CompileOptions& options);

// Format names ("rgba16f") ↔ VkFormat; bytes per texel.
VkFormat format_from_name(std::string_view name);  // VK_FORMAT_UNDEFINED when unknown
std::string format_name(VkFormat format);
std::vector<std::string> format_names();
uint32_t format_texel_bytes(VkFormat format);
bool is_depth_format(VkFormat format);

std::string kind_name(ResourceKind kind);
std::string access_name(Access access);
bool access_writes(Access access);
bool access_reads(Access access);

// The state a slot's access needs: layout, stages and access flags.
ResourceState state_for(Access access, uint32_t stages, ResourceKind kind, VkFormat format);

// A parameter value given as text (--set, the viewer) checked against its spec.
// Throws GraphError naming `key`.
ParamValue parse_param_value(const ParamSpec& spec, const std::string& key,
                             const std::string& text);
// The same for a number (Bool: non-zero is true; Enum: a choice index). Throws GraphError.
ParamValue param_from_number(const ParamSpec& spec, const std::string& key, double number);
// Shortest readable text of a number ("0.2", "1024").
std::string format_number(double v);

}  // namespace voxgi::graph
