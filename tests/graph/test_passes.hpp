#pragma once
// Pass types for compiler tests: real declarations, registered straight into a Registry. The
// compiler only reads their PassTypeInfo; these tests never execute them.

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "engine/graph/compiler.hpp"
#include "engine/graph/graph_desc.hpp"
#include "engine/graph/pass.hpp"

namespace voxgi::graph::test {

class DeclarationOnlyPass : public Pass {
 public:
  void execute(PassContext&) override {}
};

inline SlotSpec slot(std::string name, ResourceKinds kinds, Access access, uint32_t stages,
                     bool optional = false, std::vector<VkFormat> formats = {}) {
  SlotSpec s;
  s.name = std::move(name);
  s.kinds = kinds;
  s.access = access;
  s.stages = stages;
  s.optional = optional;
  s.formats = std::move(formats);
  return s;
}

inline void add_type(Registry& registry, std::string type, std::vector<SlotSpec> inputs,
                     std::vector<SlotSpec> outputs, std::vector<ParamSpec> params = {}) {
  PassTypeInfo info;
  info.type = std::move(type);
  info.doc = "test pass";
  info.inputs = std::move(inputs);
  info.outputs = std::move(outputs);
  info.params = std::move(params);
  registry.add(std::move(info), [] { return std::make_unique<DeclarationOnlyPass>(); });
}

inline ParamSpec param(std::string name, ParamType type, double def, double min = 0, double max = 0,
                       std::vector<std::string> choices = {}) {
  ParamSpec p;
  p.name = std::move(name);
  p.type = type;
  p.default_value = def;
  p.min = min;
  p.max = max;
  p.choices = std::move(choices);
  return p;
}

constexpr ResourceKinds kImages = static_cast<uint32_t>(ResourceKind::Image2D) |
                                  static_cast<uint32_t>(ResourceKind::Image3D) |
                                  static_cast<uint32_t>(ResourceKind::Clipmap);
constexpr ResourceKinds kImage2D = static_cast<uint32_t>(ResourceKind::Image2D);
constexpr ResourceKinds kBuffer = static_cast<uint32_t>(ResourceKind::Buffer);

inline Registry make_registry() {
  Registry r;
  add_type(r, "test.clear", {}, {slot("color", kImage2D, Access::ColorAttachment, kStageFragment)},
           {param("value", ParamType::Float, 0.5, 0.0, 1.0),
            param("count", ParamType::Int, 1, 1, 8), param("enabled", ParamType::Bool, 1),
            param("mode", ParamType::Enum, 0, 0, 0, {"fast", "slow"})});
  add_type(r, "test.depth", {},
           {slot("depth", kImage2D, Access::DepthAttachment, kStageFragment, false,
                 {VK_FORMAT_D32_SFLOAT})});
  add_type(r, "test.blur",
           {slot("src", kImages, Access::Sampled, kStageCompute),
            slot("extra", kImages, Access::Sampled, kStageCompute, true)},
           {slot("dst", kImages, Access::StorageWrite, kStageCompute)});
  add_type(r, "test.shade",
           {slot("src", kImages, Access::Sampled, kStageFragment),
            slot("extra", kImages, Access::Sampled, kStageFragment, true)},
           {slot("color", kImage2D, Access::ColorAttachment, kStageFragment, false,
                 {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R16G16B16A16_SFLOAT})});
  add_type(r, "test.mip", {slot("src", kImages, Access::StorageRead, kStageCompute)},
           {slot("dst", kImages, Access::StorageWrite, kStageCompute)});
  add_type(r, "test.accumulate", {slot("src", kImages, Access::Sampled, kStageCompute, true)},
           {slot("acc", kImages, Access::StorageReadWrite, kStageCompute)});
  add_type(r, "test.fill", {}, {slot("buf", kBuffer, Access::StorageWrite, kStageCompute)});
  add_type(r, "test.use_buffer", {slot("buf", kBuffer, Access::UniformRead, kStageCompute)},
           {slot("dst", kImages, Access::StorageWrite, kStageCompute)});
  // Sizes its outputs from its parameters and the viewport (SlotSpec::size_rule): a clipmap of
  // `levels` levels of `resolution`^3, a buffer of 16 bytes per voxel of a level, an image of
  // the viewport in one of two formats.
  {
    PassTypeInfo info;
    info.type = "test.sized";
    info.doc = "test pass";
    info.outputs = {slot("volume", kImages, Access::StorageWrite, kStageCompute, false,
                         {VK_FORMAT_R16G16B16A16_SFLOAT}),
                    slot("records", kBuffer, Access::StorageWrite, kStageCompute, true),
                    slot("color", kImage2D, Access::StorageWrite, kStageCompute, true,
                         {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R16G16B16A16_SFLOAT}),
                    slot("unsizable", kImages, Access::StorageWrite, kStageCompute, true)};
    ParamSpec resolution = param("resolution", ParamType::Int, 0, 0, 256);
    resolution.sizes_outputs = true;
    resolution.live = false;
    ParamSpec levels = param("levels", ParamType::Int, 1, 0, 8);
    levels.sizes_outputs = true;
    levels.live = false;
    info.params = {resolution, levels};
    set_size_rule(info, "volume", [](const SizeQuery& q) {
      DerivedSize size;
      size.resolution = static_cast<uint32_t>(q.number("resolution"));
      size.levels = static_cast<uint32_t>(q.number("levels"));
      if (size.resolution == 0) size.unavailable = "parameter 'resolution' is 0";
      return size;
    });
    set_size_rule(info, "records", [](const SizeQuery& q) {
      DerivedSize size;
      const auto edge = static_cast<VkDeviceSize>(q.number("resolution"));
      size.bytes = edge * edge * edge * 16;
      return size;
    });
    set_size_rule(info, "color", viewport_size(2));
    r.add(std::move(info), [] { return std::make_unique<DeclarationOnlyPass>(); });
  }
  // Writes an image laid out as its input, with a full mip chain.
  {
    PassTypeInfo info;
    info.type = "test.follow";
    info.doc = "test pass";
    info.inputs = {slot("src", kImages, Access::Sampled, kStageCompute)};
    info.outputs = {slot("dst", kImages, Access::StorageWrite, kStageCompute, false,
                         {VK_FORMAT_R16G16B16A16_SFLOAT})};
    set_size_rule(info, "dst", same_layout_as("src", true));
    r.add(std::move(info), [] { return std::make_unique<DeclarationOnlyPass>(); });
  }
  // vkCmdDispatchIndirect with arguments another pass wrote.
  add_type(r, "test.indirect_dispatch",
           {slot("args", kBuffer, Access::IndirectRead, kStageCompute),
            slot("data", kBuffer, Access::StorageRead, kStageCompute, true)},
           {slot("dst", kImages, Access::StorageWrite, kStageCompute)});
  return r;
}

// One registry of the test pass types per test binary, made on first use.
inline const Registry& shared_registry() {
  static const Registry registry = make_registry();
  return registry;
}

inline const char* kTestFile = "graphs/test.json";

inline CompiledGraph compile_text(const std::string& text, const Registry& registry,
                                  CompileOptions options = {}) {
  if (options.viewport_width == 1280) {
    options.viewport_width = 64;
    options.viewport_height = 32;
  }
  return compile(parse_graph(text, kTestFile), registry, options);
}

// A graph file with the images "hdr" (rgba16f) and "ldr" (rgba8, the output "display") of
// 8x8 texels, the given further resources (each ending in a comma) and passes.
inline std::string graph_text(const std::string& resources, const std::string& passes) {
  return R"({ "resources": {
    "hdr": { "type": "image2d", "format": "rgba16f", "size": 8 },
    "ldr": { "type": "image2d", "format": "rgba8", "size": 8 },)" +
         resources + R"( },
  "passes": [)" +
         passes + R"(],
  "outputs": { "display": "ldr" } })";
}

// Every error compiling `text` gives, formatted; a test failure when it compiles.
inline std::vector<std::string> compile_errors(const std::string& text, const Registry& registry,
                                               CompileOptions options = {}) {
  try {
    compile_text(text, registry, options);
  } catch (const GraphError& e) {
    std::vector<std::string> lines;
    for (const Diagnostic& d : e.diagnostics()) lines.push_back(format(d));
    return lines;
  }
  ADD_FAILURE() << "graph compiled without errors:\n" << text;
  return {};
}

// The one error compiling `text` must give.
inline std::string single_compile_error(const std::string& text, const Registry& registry,
                                        CompileOptions options = {}) {
  const std::vector<std::string> errors = compile_errors(text, registry, options);
  EXPECT_EQ(errors.size(), 1u) << ::testing::PrintToString(errors);
  return errors.empty() ? std::string() : errors.front();
}

}  // namespace voxgi::graph::test
