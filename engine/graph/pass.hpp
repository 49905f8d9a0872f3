#pragma once
// The contract between the render graph and pass plugins.
//
// A pass type is a C++ class registered under a name ("family.pass") together with a
// PassTypeInfo that declares its inputs, outputs and parameters. The graph compiler only
// ever looks at PassTypeInfo; the executor creates Pass objects through the registry and
// hands them a PassContext. Passes never create graph resources and never write barriers
// for graph resources: what they declare is what the graph synchronises.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/graph/frame.hpp"

namespace voxgi::gpu {
class Context;
class Image;
class Buffer;
class ShaderCompiler;
}  // namespace voxgi::gpu

namespace voxgi::scene {
struct Scene;
class GpuScene;
class GpuBvh;
}  // namespace voxgi::scene

namespace voxgi::graph {

// Bumped whenever PassTypeInfo, Pass, PassContext or Registry change layout or meaning.
inline constexpr uint32_t kPluginAbiVersion = 4;

enum class ParamType { Bool, Int, Float, Enum };
// "bool", "int", "float" or "enum".
const char* param_type_name(ParamType type);

struct ParamSpec {
  std::string name;
  ParamType type = ParamType::Float;
  double default_value = 0.0;  // Enum: index into choices
  double min = 0.0;            // inclusive range for Int and Float
  double max = 0.0;
  std::vector<std::string> choices;  // Enum only
  std::string doc;
  // false: a change re-runs the pass's setup() (e.g. it changes a shader define).
  bool live = true;
  // A slot's size rule reads it: a change takes a recompile (Executor::set_param refuses it
  // with ParamNeedsRecompile; --set and the viewer rebuild the graph).
  bool sizes_outputs = false;
};

struct ParamValue {
  double number = 0.0;  // Bool: 0/1, Int, Float, Enum: index
  std::string text;     // Enum: the choice's name
};

enum class ResourceKind : uint32_t { Image2D = 1, Image3D = 2, Clipmap = 4, Buffer = 8 };
using ResourceKinds = uint32_t;
constexpr ResourceKinds kinds(ResourceKind k) {
  return static_cast<uint32_t>(k);
}
constexpr ResourceKinds operator|(ResourceKind a, ResourceKind b) {
  return static_cast<uint32_t>(a) | static_cast<uint32_t>(b);
}

// How a pass touches a resource bound to a slot. Inputs use read accesses, outputs write ones.
enum class Access {
  Sampled,           // image read through a sampler (depth images: also comparison samplers)
  StorageRead,       // storage image or storage buffer, read only
  StorageWrite,      // storage image or storage buffer, fully overwritten
  StorageReadWrite,  // storage image or buffer, read-modify-write (keeps previous contents)
  ColorAttachment,   // render target, cleared or overwritten
  DepthAttachment,   // depth render target, written and tested
  UniformRead,       // uniform buffer
  TransferRead,
  TransferWrite,
  // Buffer of indirect arguments read by vkCmdDispatchIndirect or vkCmdDraw*Indirect (input
  // slots of buffers only). It synchronises with the draw-indirect stage whatever the slot's
  // stages say, since the command, not a shader, reads it.
  IndirectRead,
};

// Shader stages a slot is used in (bit mask).
enum Stage : uint32_t {
  kStageVertex = 1,
  kStageGeometry = 2,
  kStageFragment = 4,
  kStageCompute = 8,
  kStageTransfer = 16,
};

struct ResourceInfo;

// What a slot's size rule sees while the graph compiles: the pass's parameters as resolved,
// the resources bound to its other slots (those already sized), scene features and the
// viewport.
struct SizeQuery {
  const std::map<std::string, ParamValue>* params = nullptr;
  std::function<const ResourceInfo*(std::string_view slot)> bound;  // nullptr: unbound/unsized
  std::function<bool(std::string_view slot)> has;                   // bound, sized or not
  const std::map<std::string, double>* scene = nullptr;             // "scene.light_count" → n
  uint32_t viewport_width = 0;
  uint32_t viewport_height = 0;

  double number(std::string_view param) const;
  std::string choice(std::string_view param) const;    // an enum's choice; empty when absent
  double scene_value(std::string_view feature) const;  // 0 when absent
};

// The size an output needs, for a resource the graph declares without one. Only the fields of
// the resource's kind are read; what the graph does give (mips, layers) wins.
struct DerivedSize {
  VkDeviceSize bytes = 0;                     // buffer
  uint32_t width = 0, height = 0, depth = 0;  // image2d (depth unused), image3d
  uint32_t layers = 0;                        // image2d array layers; 0: one
  uint32_t resolution = 0, levels = 0;        // clipmap
  bool full_mips = false;                     // a full mip chain unless the graph says
  std::string unavailable;                    // non-empty: why it cannot be derived
};
using SizeRule = std::function<DerivedSize(const SizeQuery&)>;

// Size rules for common cases: the viewport (or a fraction of it), and the same layout as the
// resource bound to another slot (a clipmap's resolution and levels, an image's extent).
SizeRule viewport_size(uint32_t divisor = 1);
SizeRule same_layout_as(std::string slot, bool full_mips = false);

struct SlotSpec {
  std::string name;
  ResourceKinds kinds = 0;
  Access access = Access::Sampled;
  uint32_t stages = kStageFragment;
  std::vector<VkFormat> formats;  // empty: any format
  bool optional = false;
  std::string doc;
  // Outputs only: working memory whose contents mean nothing after the pass. It may be
  // transient even when the pass may skip or read-modify-writes it, so the pass must not rely
  // on earlier contents unless the resource is persistent.
  bool scratch = false;
  // Outputs only: the size the pass needs, used when the graph declares the resource without
  // one (docs/design.md, "Pass-owned sizes"). May be empty.
  SizeRule size_rule;
};

struct CompiledPass;
class PassCheck;
struct PassTypeInfo;

// Gives the output slot `slot` of `info` a size rule; throws std::logic_error when the type has
// no such output (a mistake in the pass type's registration).
void set_size_rule(PassTypeInfo& info, std::string_view slot, SizeRule rule);

// Checks of a pass's parameters and bound slots that the declarations cannot express; the
// compiler runs it for every pass of a graph file, so problems show up in `voxgi graph check`.
using PassValidator = std::function<void(PassCheck& check)>;

struct PassTypeInfo {
  std::string type;  // "family.pass"
  std::string doc;
  std::vector<SlotSpec> inputs;
  std::vector<SlotSpec> outputs;
  std::vector<ParamSpec> params;
  // The pass may skip a frame whose inputs did not change (Pass::skip_reason), leaving what it
  // writes as the previous frame left it; the compiler then requires every output it writes,
  // scratch slots aside, to be persistent.
  bool may_skip = false;
  PassValidator validate;  // may be empty
};

// What a slot is bound to, as compiled: sizes are resolved.
struct ResourceInfo {
  std::string name;  // the graph resource's name
  ResourceKind kind = ResourceKind::Image2D;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent3D extent{0, 0, 0};  // clipmap: (R, R, R * levels), levels stacked along z
  uint32_t mip_levels = 1;
  uint32_t array_layers = 1;
  uint32_t clipmap_levels = 0;   // clipmap only
  VkDeviceSize buffer_size = 0;  // buffer only
  int mip = -1;                  // the single mip the slot touches, -1 for all
  bool persistent = false;
};

// The live resource behind a slot during execute().
struct BoundResource {
  const ResourceInfo* info = nullptr;
  gpu::Image* image = nullptr;                       // images and clipmaps
  gpu::Buffer* buffer = nullptr;                     // buffers
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // the layout the graph put it in
  VkImageView view = VK_NULL_HANDLE;                 // whole image, or the single mip of info->mip
};

class PassContextImpl;

// A pass as the graph declares it: its name, resolved parameters and bound slots. The type's
// validate hook sees it through PassCheck when the graph compiles, the pass through PassContext.
class PassDeclaration {
 public:
  explicit PassDeclaration(const CompiledPass& pass) : pass_(pass) {}

  const std::string& pass_name() const;
  bool has(std::string_view slot) const;  // false for an unbound optional slot
  const ResourceInfo& info(std::string_view slot) const;

  double number(std::string_view param) const;
  int integer(std::string_view param) const { return static_cast<int>(number(param)); }
  bool flag(std::string_view param) const { return number(param) != 0.0; }
  const std::string& choice(std::string_view param) const;

 protected:
  const CompiledPass& pass_;
};

// What a pass type's validate hook reports to: each problem becomes a compile error located at
// the parameter's or slot's place in the graph file (the pass's when it is not written there).
class PassCheck : public PassDeclaration {
 public:
  using Report = std::function<void(const std::string& field, std::string message)>;
  PassCheck(const CompiledPass& pass, Report report)
      : PassDeclaration(pass), report_(std::move(report)) {}

  void param_error(std::string_view param, std::string message);
  void slot_error(std::string_view slot, std::string message);

 private:
  Report report_;
};

// Everything a pass may use. Valid during setup() and execute(); cmd() and resource() only
// during execute().
class PassContext : public PassDeclaration {
 public:
  explicit PassContext(PassContextImpl& impl);

  gpu::Context& gpu() const;
  gpu::ShaderCompiler& shaders() const;
  const scene::Scene& scene() const;
  scene::GpuScene& gpu_scene() const;
  // The scene's BVH, shared by every pass that traces rays (GpuScene::bvh): built on first use,
  // refit when instances moved. Bind its buffers as docs/design.md describes.
  const scene::GpuBvh& scene_bvh() const;
  const FrameInfo& frame() const;

  const BoundResource& resource(std::string_view slot) const;

  // True when a parameter of this pass changed since the previous execute().
  bool params_changed() const;
  // How many times a pass writing the slot's resource has executed (skipped runs do not count),
  // kept across rebuilds for resources of the same name. A pass that stores the versions it
  // consumed can tell that none of its inputs changed. 0 for an unbound optional slot.
  uint64_t resource_version(std::string_view slot) const;

  VkCommandBuffer cmd() const;
  // A barrier between two of this pass's own dispatches or draws on a resource it owns for the
  // pass (e.g. building a mip chain level by level). Graph-level barriers are not the pass's job.
  void barrier_within_pass(std::string_view slot, int src_mip = -1, int dst_mip = -1) const;

 private:
  PassContextImpl& impl_;
};

class Pass {
 public:
  virtual ~Pass() = default;
  // Create pipelines; runs after each compile and after a non-live parameter change.
  virtual void setup(PassContext& ctx) { (void)ctx; }
  // Record commands into ctx.cmd().
  virtual void execute(PassContext& ctx) = 0;
  // Non-empty: the pass skips this frame because its inputs did not change; the reason is
  // reported by timings. Only types declaring may_skip may skip. Asked before anything of the
  // frame is recorded, in schedule order, with resource versions as the passes before it leave
  // them, so that no barrier is recorded for what a skipped pass would have written.
  virtual std::string skip_reason(const PassContext& ctx) const {
    (void)ctx;
    return {};
  }
};

using PassFactory = std::function<std::unique_ptr<Pass>()>;

class Registry {
 public:
  // Throws std::invalid_argument when the type is already registered.
  void add(PassTypeInfo info, PassFactory factory);
  const PassTypeInfo* find(std::string_view type) const;
  std::unique_ptr<Pass> create(std::string_view type) const;
  std::vector<const PassTypeInfo*> all() const;  // sorted by type name

 private:
  struct Entry {
    PassTypeInfo info;
    PassFactory factory;
  };
  std::vector<Entry> entries_;
};

}  // namespace voxgi::graph

// Every pass family library exports these two C functions.
//   voxgi_plugin_abi_version() returns kPluginAbiVersion of the headers it was built with;
//   voxgi_plugin_register() adds the family's pass types.
extern "C" {
using VoxgiPluginAbiVersionFn = uint32_t (*)();
using VoxgiPluginRegisterFn = void (*)(voxgi::graph::Registry&);
}
#define VOXGI_PLUGIN_EXPORT extern "C" __attribute__((visibility("default")))
